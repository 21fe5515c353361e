// libFuzzer target: the whole pipeline on tiny scenes, every map checked by the
// independent exact checker (scripts/fuzz.sh pipeline). VISMAP_FUZZ_ENGINE=
// franklin (default), newell or both picks the engine(s).
#include "tests/fuzz/fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 256) return -1;  // a tiny scene never needs more
  static const vismap_fuzz::Engines engines = vismap_fuzz::engines_from_env();
  vismap_fuzz::check_pipeline(data, size, engines);
  return 0;
}
