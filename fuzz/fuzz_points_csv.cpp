// Fuzz target: points files (CSV with x, y, z columns), reconstruction/io/points_csv.
#include "fuzz_support.h"

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/points_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    const Eigen::MatrixX3d P = parse_points_csv(fuzz::text(data, size), "fuzz.csv");
    if (P.rows() < 1 || !P.allFinite())
      std::abort();
  });
  return 0;
}
