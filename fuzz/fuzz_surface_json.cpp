// Fuzz target: surface JSON files, reconstruction/io/surface_json; a surface that is accepted is
// evaluated at its domain corners and centre.
#include "fuzz_support.h"
#include "probe_surface.h"

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/surface_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    std::map<std::string, std::string> meta;
    const BSplineSurface s = parse_surface_json(fuzz::text(data, size), "fuzz.json", &meta);
    fuzz::probe_surface(s);
  });
  return 0;
}
