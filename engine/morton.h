// Position along a Morton (Z-order) curve: stages that walk facets and curves in
// this order touch memory in screen order, which keeps large scenes in cache.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/parallel.h"

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
// radix sort, two passes of 16 bits, each pass's parts counted and placed side
// by side on `threads` threads (a comparison sort of (key, position) pairs
// gives the same order at about ten times the cost).
inline std::vector<std::uint32_t> order_by_key(const std::vector<std::uint32_t>& key, int threads) {
  const int n = static_cast<int>(key.size());
  constexpr std::size_t kBuckets = std::size_t{1} << 16;
  auto at = [](int i) { return static_cast<std::size_t>(i); };
  const Buckets low = bucket_items(n, kBuckets, threads, [&](int i, auto&& in) { in(key[at(i)] & 0xffff); });
  const std::vector<std::uint32_t>& by_low = low.items;
  const Buckets high = bucket_items(n, kBuckets, threads, [&](int k, auto&& in) { in(key[by_low[at(k)]] >> 16); });
  std::vector<std::uint32_t> order(key.size());
  parallel_chunks(n, 65536, threads, [&](int, Chunk r) {
    for (int k = r.begin; k < r.end; ++k) order[at(k)] = by_low[high.items[at(k)]];
  });
  return order;
}

}  // namespace vismap::engine
