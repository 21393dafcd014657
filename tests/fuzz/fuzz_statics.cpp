// libFuzzer target: the statics input end to end (tests/fuzz/fuzz_inputs.h). Crashes, sanitizer
// reports, uncaught exceptions other than InputError/SimulationError, and NaN abort.
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "tests/fuzz/fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    cablelab::fuzz::runStaticsInput(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const cablelab::fuzz::HarnessFailure& e) {
    std::fprintf(stderr, "fuzz_statics: %s\n", e.what());
    std::abort();
  }
  return 0;
}
