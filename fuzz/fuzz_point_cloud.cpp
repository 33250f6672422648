// Fuzz target: point-cloud files (reconstruction/clouds/read_point_cloud): every input is parsed
// as each format (.pcd, .ply, .xyz, .xyzn, .csv), ASCII and binary flavours alike.
#include "fuzz_support.h"

#include "interlin/reconstruction/clouds/read_point_cloud.h"
#include "interlin/reconstruction/io/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  const std::string text = fuzz::text(data, size);
  for (const char* name : {"fuzz.pcd", "fuzz.ply", "fuzz.xyz", "fuzz.xyzn", "fuzz.csv"})
    fuzz::only_throws<InputError>([&] {
      const PointCloud c = parse_point_cloud(text, name);
      if (c.points.rows() < 1 || !c.points.allFinite() ||
          (c.has_normals() && (c.normals.rowwise().norm().array() - 1).abs().maxCoeff() > 1e-9))
        std::abort();
    });
  return 0;
}
