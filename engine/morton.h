// Position along a Morton (Z-order) curve: stages that walk facets and curves in
// this order touch memory in screen order, which keeps large scenes in cache.
#pragma once
#include <algorithm>
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
// LSD radix sort of (key, position) pairs packed in 64 bits, three passes of
// 11 key bits, each a counted_placement on `threads` threads. (2^11 buckets a
// pass keep the places written to in cache: two passes of 2^16 took ~6 times
// as long on 10^6 facets, their writes scattered over 2^16 places and their
// second pass gathering keys; a comparison sort of the pairs gives the same
// order at about ten times the cost.)
inline std::vector<std::uint32_t> order_by_key(const std::vector<std::uint32_t>& key, int threads) {
  const int n = static_cast<int>(key.size());
  auto at = [](int i) { return static_cast<std::size_t>(i); };
  std::vector<std::uint64_t> pairs(key.size()), placed(key.size());
  parallel_chunks(n, 65536, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) pairs[at(i)] = std::uint64_t{key[at(i)]} << 32 | static_cast<std::uint32_t>(i);
  });
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
  for (int shift = 32; shift < 64; shift += kDigit) {
    counted_placement(
        n, kBuckets, threads,
        [&](int i, auto&& visit) { visit(static_cast<std::size_t>(pairs[at(i)] >> shift) & (kBuckets - 1)); },
        [](std::uint32_t) {}, [&](int i, std::uint32_t slot) { placed[slot] = pairs[at(i)]; });
    pairs.swap(placed);
  }
  std::vector<std::uint64_t>().swap(placed);
  std::vector<std::uint32_t> order(key.size());
  parallel_chunks(n, 65536, threads, [&](int, Chunk r) {
    for (int k = r.begin; k < r.end; ++k) order[at(k)] = static_cast<std::uint32_t>(pairs[at(k)]);
  });
  return order;
}

}  // namespace vismap::engine
