// Fuzz targets mesh_ply and mesh_obj: the PLY and OBJ mesh readers of interlin
// (reconstruction/io/mesh_formats) through parse_mesh; FUZZ_FILE ("fuzz.ply" or "fuzz.obj") picks
// the format. An accepted mesh must be finite and index only its own vertices.
#include "fuzz_support.h"

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    parse_mesh(fuzz::text(data, size), FUZZ_FILE, V, F);
    if (!V.allFinite() || (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows())))
      std::abort();
  });
  return 0;
}
