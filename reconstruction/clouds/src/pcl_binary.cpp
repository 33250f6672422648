// Binary PCD / PLY payloads through PCL's readers (pcl::PCDReader, pcl::PLYReader). Only called
// after the header has been validated against the file size (pcd_file.cpp, ply_file.cpp): PCL
// allocates whatever a header declares and crashes on some malformed headers.
#include "cloud_formats.h"

#include "interlin/reconstruction/io/input_error.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <cstring>
#include <limits>
#include <mutex>

namespace interlin::detail {

namespace {

// Field `f` of point `i` as a double, whatever its PCL datatype.
double field_value(const pcl::PCLPointCloud2& c, const pcl::PCLPointField& f, std::size_t i) {
  const std::uint8_t* p = c.data.data() + i * c.point_step + f.offset;
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  switch (f.datatype) {
  case pcl::PCLPointField::INT8:
    return get(std::int8_t{});
  case pcl::PCLPointField::UINT8:
    return get(std::uint8_t{});
  case pcl::PCLPointField::INT16:
    return get(std::int16_t{});
  case pcl::PCLPointField::UINT16:
    return get(std::uint16_t{});
  case pcl::PCLPointField::INT32:
    return get(std::int32_t{});
  case pcl::PCLPointField::UINT32:
    return get(std::uint32_t{});
  case pcl::PCLPointField::FLOAT32:
    return get(float{});
  case pcl::PCLPointField::FLOAT64:
    return get(double{});
  default:
    return std::numeric_limits<double>::quiet_NaN();
  }
}

} // namespace

Eigen::MatrixXd pcl_binary_fields(const std::string& path, bool ply,
                                  const std::vector<std::string>& names) {
  pcl::PCLPointCloud2 c;
  int status = 0;
  {
    // PCL prints its own diagnostics on stderr; the reader reports one line instead.
    static std::mutex m;
    const std::lock_guard<std::mutex> lock(m);
    const pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel();
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    if (ply) {
      pcl::PLYReader r;
      status = r.read(path, c);
    } else {
      pcl::PCDReader r;
      status = r.read(path, c);
    }
    pcl::console::setVerbosityLevel(level);
  }
  if (status < 0)
    throw_input_error(path, 0,
                      std::string("PCL cannot decode the binary ") + (ply ? "PLY" : "PCD") +
                          " data (truncated or corrupt)");
  const std::size_t n = std::size_t(c.width) * c.height;
  if (c.data.size() < n * c.point_step)
    throw_input_error(path, 0, "PCL decoded less data than the header declares");
  Eigen::MatrixXd F(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(names.size()));
  for (std::size_t k = 0; k < names.size(); ++k) {
    const pcl::PCLPointField* f = nullptr;
    for (const pcl::PCLPointField& g : c.fields)
      if (g.name == names[k])
        f = &g;
    if (!f)
      throw_input_error(path, 0, "PCL found no field " + names[k] + " in the binary data");
    for (std::size_t i = 0; i < n; ++i)
      F(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = field_value(c, *f, i);
  }
  return F;
}

} // namespace interlin::detail
