// Fuzz target: IGES files read back (first entity 128), reconstruction/io/iges; a surface that
// is accepted is evaluated at its domain corners and centre.
#include "fuzz_support.h"
#include "probe_surface.h"

#include "interlin/reconstruction/io/iges.h"
#include "interlin/reconstruction/io/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    const BSplineSurface s = parse_iges_surface(fuzz::text(data, size), "fuzz.igs");
    fuzz::probe_surface(s);
  });
  return 0;
}
