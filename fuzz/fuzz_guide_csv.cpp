// Fuzz target: guide-line files (CSV guide,index,x,y,z), reconstruction/io/guide_csv.
#include "fuzz_support.h"

#include "interlin/reconstruction/io/guide_csv.h"
#include "interlin/reconstruction/io/input_error.h"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    std::istringstream in(fuzz::text(data, size));
    const GuideSet g = parse_guides(in, "fuzz.csv");
    for (const Guide& guide : g.guides)
      if (guide.points.rows() < 2 || !guide.points.allFinite())
        std::abort();
  });
  return 0;
}
