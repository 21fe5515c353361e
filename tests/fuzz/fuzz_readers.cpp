// The readers' fuzz property (no engine code: the reader targets build without CGAL).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "tests/fuzz/fuzz_harness.h"

namespace vismap_fuzz {

void die(const std::string& why) {
  std::fprintf(stderr, "\n*** vismap fuzz finding: %s\n", why.c_str());
  std::fflush(stderr);
  std::abort();
}

void check_reader(const std::uint8_t* data, std::size_t size, const std::string& format) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  vismap::Scene s;
  try {
    s = vismap::read_scene_bytes(bytes, "fuzz." + format, format);
  } catch (const vismap::InputError& e) {
    const std::string msg = e.what();
    if (msg.rfind("fuzz." + format, 0) != 0) die("an error message that does not name the file: " + msg);
    return;
  }
  for (const vismap::Vec3& v : s.vertices) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) die("a non-finite coordinate was read");
  }
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (s.faces[f].size() < 3) die("face " + std::to_string(f) + " has fewer than 3 corners");
    for (std::uint32_t i : s.faces[f]) {
      if (i >= s.vertices.size()) die("face " + std::to_string(f) + " has an index out of range");
    }
  }
}

}  // namespace vismap_fuzz
