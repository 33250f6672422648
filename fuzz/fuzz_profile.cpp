// Fuzz targets profile_json and profile_toml: cascade profile parameter files (interlin profile
// PARAMS.json|toml), tools/profile_parameters and, for TOML, tools/toml_as_json; FUZZ_FILE
// ("fuzz.json" or "fuzz.toml") picks the syntax.
#include "fuzz_support.h"

#include "profile_parameters.h"

#include "interlin/interflatation/input_error.h"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    const bool toml = std::string_view(FUZZ_FILE).ends_with(".toml");
    const cli::ProfileJob job =
        cli::parse_profile_parameters(fuzz::text(data, size), FUZZ_FILE, toml);
    if (job.stations.empty())
      std::abort();
  });
  return 0;
}
