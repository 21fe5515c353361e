// libFuzzer target: the OFF reader on arbitrary bytes (scripts/fuzz.sh read_off).
#include "tests/fuzz/fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vismap_fuzz::check_reader(data, size, "off");
  return 0;
}
