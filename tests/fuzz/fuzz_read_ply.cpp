// libFuzzer target: the PLY reader on arbitrary bytes (scripts/fuzz.sh read_ply).
#include "tests/fuzz/fuzz_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vismap_fuzz::check_reader(data, size, "ply");
  return 0;
}
