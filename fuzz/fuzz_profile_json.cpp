// Fuzz target: cascade profile parameter files in JSON (interlin profile PARAMS.json),
// tools/profile_parameters.
#include "fuzz_support.h"

#include "profile_parameters.h"

#include "interlin/interflatation/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin;
  fuzz::only_throws<InputError>([&] {
    const cli::ProfileJob job =
        cli::parse_profile_parameters(fuzz::text(data, size), "fuzz.json", false);
    if (job.stations.empty())
      std::abort();
  });
  return 0;
}
