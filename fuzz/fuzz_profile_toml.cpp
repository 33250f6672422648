// Fuzz target: cascade profile parameter files in TOML (interlin profile PARAMS.toml),
// tools/profile_parameters and tools/toml_as_json.
#include "fuzz_support.h"

#include "profile_parameters.h"

#include "interlin/interflatation/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    const cli::ProfileJob job =
        cli::parse_profile_parameters(fuzz::text(data, size), "fuzz.toml", true);
    if (job.stations.empty())
      std::abort();
  });
  return 0;
}
