// Position along a Morton (Z-order) curve: stages that walk facets and curves in
// this order touch memory in screen order, which keeps large scenes in cache.
#pragma once
#include <cstdint>
#include <vector>

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

// The positions 0..n-1 ordered by key[i], ties in position order: a stable
// radix sort, two passes of 16 bits (a comparison sort of (key, position)
// pairs gives the same order at about ten times the cost).
inline std::vector<std::uint32_t> order_by_key(const std::vector<std::uint32_t>& key) {
  const std::size_t n = key.size();
  std::vector<std::uint32_t> order(n), pass(n);
  for (std::size_t i = 0; i < n; ++i) pass[i] = static_cast<std::uint32_t>(i);
  for (const int shift : {0, 16}) {
    std::vector<std::uint32_t> start(std::size_t{1} << 16 | 1, 0);
    for (std::uint32_t k : key) ++start[((k >> shift) & 0xffff) + 1];
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    for (std::uint32_t i : pass) order[start[(key[i] >> shift) & 0xffff]++] = i;
    pass.swap(order);
  }
  return pass;
}

}  // namespace vismap::engine
