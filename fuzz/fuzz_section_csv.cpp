// Fuzz target: section files (CSV with header or plain x y z), reconstruction/io/section_csv.
#include "fuzz_support.h"

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/section_csv.h"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    std::istringstream in(fuzz::text(data, size));
    const SectionSet s = parse_sections(in, "fuzz.csv");
    for (const Section& sec : s.sections) // the documented guarantees of a successful read
      if (sec.points.rows() < 4 || !sec.points.allFinite() ||
          sec.lines.size() != static_cast<std::size_t>(sec.points.rows()))
        std::abort();
  });
  return 0;
}
