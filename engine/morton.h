// Position along a Morton (Z-order) curve: stages that walk facets and curves in
// this order touch memory in screen order, which keeps large scenes in cache.
#pragma once
#include <cstdint>

namespace vismap::engine {

// A point of the unit square (clamped; NaN counts as 0), 16 bits per axis.
inline std::uint32_t morton(double u, double v) {
  auto spread = [](std::uint32_t x) {
    x &= 0xffff;
    x = (x | (x << 8)) & 0x00ff00ff;
    x = (x | (x << 4)) & 0x0f0f0f0f;
    x = (x | (x << 2)) & 0x33333333;
    return (x | (x << 1)) & 0x55555555;
  };
  auto q = [](double t) { return static_cast<std::uint32_t>((t > 0 ? (t < 1 ? t : 1) : 0) * 65535.0); };
  return spread(q(u)) | (spread(q(v)) << 1);
}

}  // namespace vismap::engine
