// libFuzzer target: the OBJ reader on arbitrary bytes (scripts/fuzz.sh read_obj).
#include "tests/fuzz/fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vismap_fuzz::check_reader(data, size, "obj");
  return 0;
}
