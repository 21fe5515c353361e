// The engine's threads: loops whose iterations are independent, run on OpenMP
// (GCC's libgomp, or LLVM's libomp under clang). Internal to the engine.
//
// What keeps the output identical for every thread count: an iteration writes
// only its own slot (a cell's, a curve's, a chunk's), and the caller merges the
// slots in index order, as the serial loop would have produced them. Nothing an
// iteration decides depends on which thread ran it or when.
//
// What is per thread: the FPU rounding mode (each filtered predicate sets its
// own, engine/exact_kernel.h's UpwardRounding is thread_local), and the filter
// counters (engine/exact_config.h), which are summed into the calling thread's
// here. CGAL is built thread-safe (exact_config.h): its lazy numbers, shared by
// the iterations, count their references atomically once a second thread exists
// and evaluate their exact values once (std::call_once).
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <iterator>
#include <mutex>
#include <utility>
#include <vector>

#include <CGAL/FPU.h>

#include "engine/exact_kernel.h"
#include "engine/threads.h"
#ifdef _OPENMP
#include <omp.h>
#endif

namespace vismap::engine {

// body(i) for every i in [0, n), on `threads` threads, scheduled dynamically
// (cells and curves differ widely in work). The first exception a body throws is
// rethrown here, after the loop.
template <class Body>
void parallel_for(int n, int threads, Body&& body) {
  static_cast<void>(threads);   // (one thread without OpenMP)
#ifdef _OPENMP
  if (threads > 1 && n > 1) {
    std::exception_ptr error;
    exact::FilterCounts workers;
    std::mutex lock;
    // Each thread runs the body in the caller's rounding mode, as the serial loop
    // would (a pool thread keeps whatever mode it was left in or created with).
    const CGAL::FPU_CW_t mode = CGAL::FPU_get_cw();
    const bool upward = exact::rounding_upward;
#pragma omp parallel num_threads(std::min(threads, n))
    {
      CGAL::FPU_set_cw(mode);
      exact::rounding_upward = upward;
      const exact::FilterCounts before = exact::filter_counts;
#pragma omp for schedule(dynamic, 1)
      for (int i = 0; i < n; ++i) {
        try {
          body(i);
        } catch (...) {
          std::lock_guard<std::mutex> hold(lock);
          if (!error) error = std::current_exception();
        }
      }
      if (omp_get_thread_num() != 0) {   // (thread 0 is the caller: its counts are the total)
        std::lock_guard<std::mutex> hold(lock);
        workers.calls += exact::filter_counts.calls - before.calls;
        workers.exact += exact::filter_counts.exact - before.exact;
      }
    }
    exact::filter_counts.calls += workers.calls;
    exact::filter_counts.exact += workers.exact;
    if (error) std::rethrow_exception(error);
    return;
  }
#endif
  for (int i = 0; i < n; ++i) body(i);
}

// A pipeline: make(i) -> T for every i in [0, n) on `threads` threads, and
// take(i, made) in the order of i, one at a time, each on the thread that made
// its item: the serial takes (writing text to a file) run while the other
// threads make the next items, with no thread of their own. After a make or
// take throws, no later take runs; the first exception is rethrown here.
// (For work that asks no predicate: the threads keep their own rounding modes,
// and no filter counts are gathered.)
template <class T, class Make, class Take>
void parallel_in_order(int n, int threads, Make&& make, Take&& take) {
  static_cast<void>(threads);   // (one thread without OpenMP)
#ifdef _OPENMP
  if (threads > 1 && n > 1) {
    std::exception_ptr error;
    std::mutex lock;
    auto keep_first = [&] {
      std::lock_guard<std::mutex> hold(lock);
      if (!error) error = std::current_exception();
    };
    auto failed = [&] {
      std::lock_guard<std::mutex> hold(lock);
      return static_cast<bool>(error);
    };
#pragma omp parallel for num_threads(std::min(threads, n)) schedule(dynamic, 1) ordered
    for (int i = 0; i < n; ++i) {
      T item{};
      bool made = false;
      try {
        if (!failed()) {
          item = make(i);
          made = true;
        }
      } catch (...) {
        keep_first();
      }
#pragma omp ordered
      {
        try {
          if (made && !failed()) take(i, std::move(item));
        } catch (...) {
          keep_first();
        }
      }
    }
    if (error) std::rethrow_exception(error);
    return;
  }
#endif
  for (int i = 0; i < n; ++i) take(i, make(i));
}

// std::inplace_merge of sorted [first, middle) and [middle, last) (stable), in
// `parts` pieces side by side: the larger run's middle element splits both runs
// (binary search in the other), one rotation puts the two left parts before the
// two right ones, and the halves are merged in parallel, each the same way.
template <class It, class Less>
void parallel_inplace_merge(It first, It middle, It last, Less less, int parts) {
  if (parts < 2 || last - first < 16384 || first == middle || middle == last) {
    std::inplace_merge(first, middle, last, less);
    return;
  }
  It a_cut, b_cut;   // left: [first, a_cut) and [middle, b_cut); equal elements keep A before B
  if (middle - first >= last - middle) {
    a_cut = first + (middle - first) / 2;
    b_cut = std::lower_bound(middle, last, *a_cut, less);
  } else {
    b_cut = middle + (last - middle) / 2;
    a_cut = std::upper_bound(first, middle, *b_cut, less);
  }
  // [a_cut, b_cut) becomes B's left part, then A's right part (from `split`).
  const It split = std::rotate(a_cut, middle, b_cut);
  parallel_for(2, 2, [&](int half) {
    if (half == 0) parallel_inplace_merge(first, a_cut, split, less, parts / 2);
    else parallel_inplace_merge(split, split + (middle - a_cut), last, less, parts - parts / 2);
  });
}

// Sorts [first, last) by `less` on `threads` threads: runs sorted in parallel,
// then merged pairwise (the pairs of a round in parallel). For a strict total
// order (no two elements equivalent) the result is std::sort's, for every thread
// count; callers whose order has ties break them (by position, say).
template <class It, class Less>
void parallel_sort(It first, It last, Less less, int threads) {
  const auto n = last - first;
  int runs = 1;
  while (runs * 2 <= threads && n / (runs * 2) >= 8192) runs *= 2;
  if (runs == 1) {
    std::sort(first, last, less);
    return;
  }
  auto bound = [&](int k) { return first + n * k / runs; };
  parallel_for(runs, threads, [&](int k) { std::sort(bound(k), bound(k + 1), less); });
  for (int width = 1; width < runs; width *= 2) {
    const int pairs = runs / (2 * width);
    parallel_for(pairs, threads, [&](int p) {
      parallel_inplace_merge(bound(2 * p * width), bound((2 * p + 1) * width), bound((2 * p + 2) * width), less,
                             std::max(1, threads / pairs));
    });
  }
}

// [begin, end) of chunk k when n items are cut into chunks of `size`.
struct Chunk {
  int begin, end;
};
inline int chunk_count(int n, int size) { return (n + size - 1) / size; }
inline Chunk chunk(int k, int n, int size) { return {k * size, std::min(n, (k + 1) * size)}; }

// A counter or slot that the iterations of one parallel loop on `threads`
// threads share: a locked operation where more than one thread runs them, a
// plain one where one does (the iterations then run one after another): no
// locked instruction per item on one thread. Relaxed: the loop's end orders them.
template <class T>
T shared_fetch_add(T& x, T d, int threads) {
  if (threads <= 1) return std::exchange(x, x + d);
  return std::atomic_ref<T>(x).fetch_add(d, std::memory_order_relaxed);
}
template <class T>
bool shared_compare_exchange(T& x, T& expected, T desired, int threads) {
  if (threads > 1) return std::atomic_ref<T>(x).compare_exchange_strong(expected, desired, std::memory_order_relaxed);
  if (x != expected) {
    expected = x;
    return false;
  }
  x = desired;
  return true;
}

// body(k, chunk k) for the chunks of `size` consecutive items of [0, n), on
// `threads` threads (parallel_for); chunk k's results go to the caller's slot k.
template <class Body>
void parallel_chunks(int n, int size, int threads, Body&& body) {
  parallel_for(chunk_count(n, size), threads, [&](int k) { body(k, chunk(k, n, size)); });
}

// Items [0, n) placed bucket by bucket, stably, in two passes over parts of
// the items side by side on `threads` threads: each_bucket(i, visit) calls
// visit(b) for each bucket b item i goes in; the first pass counts each part's
// items per bucket, make_room(total) then sizes the caller's output, and the
// second pass calls place(i, slot) for each of item i's buckets: bucket b's
// items take slots first[b] .. first[b + 1] in item order, each part's after
// the parts' before, as one pass would. Returns first (buckets + 1 entries).
template <class EachBucket, class MakeRoom, class Place>
std::vector<std::uint32_t> counted_placement(int n, std::size_t buckets, int threads, EachBucket&& each_bucket,
                                             MakeRoom&& make_room, Place&& place) {
  const int parts = std::max(1, std::min(threads, n / 16384));
  auto part = [&](int k) {
    auto at = [&](int j) { return static_cast<int>(static_cast<long>(n) * j / parts); };
    return Chunk{at(k), at(k + 1)};
  };
  // Per part: each bucket's count, then where the part's next item in it goes.
  std::vector<std::vector<std::uint32_t>> next(static_cast<std::size_t>(parts));
  parallel_for(parts, threads, [&](int k) {
    std::vector<std::uint32_t> count(buckets, 0);
    const Chunk r = part(k);
    for (int i = r.begin; i < r.end; ++i) each_bucket(i, [&](std::size_t b) { ++count[b]; });
    next[static_cast<std::size_t>(k)] = std::move(count);
  });
  std::vector<std::uint32_t> first(buckets + 1, 0);
  for (std::size_t b = 0; b < buckets; ++b) {
    std::uint32_t at = first[b];
    for (std::vector<std::uint32_t>& count : next) {
      const std::uint32_t here = count[b];
      count[b] = at;
      at += here;
    }
    first[b + 1] = at;
  }
  make_room(first[buckets]);
  parallel_for(parts, threads, [&](int k) {
    std::vector<std::uint32_t>& at = next[static_cast<std::size_t>(k)];
    const Chunk r = part(k);
    for (int i = r.begin; i < r.end; ++i) each_bucket(i, [&](std::size_t b) { place(i, at[b]++); });
  });
  return first;
}

// Items [0, n) listed by bucket, in compressed rows: each_bucket(i, visit) calls
// visit(b) for each bucket b item i goes in. A bucket lists its items in item
// order (counted_placement).
struct Buckets {
  std::vector<std::uint32_t> first;   // bucket b's items: items[first[b] .. first[b + 1])
  std::vector<std::uint32_t> items;
};
template <class EachBucket>
Buckets bucket_items(int n, std::size_t buckets, int threads, EachBucket&& each_bucket) {
  Buckets out;
  out.first = counted_placement(
      n, buckets, threads, each_bucket, [&](std::uint32_t total) { out.items.resize(total); },
      [&](int i, std::uint32_t slot) { out.items[slot] = static_cast<std::uint32_t>(i); });
  return out;
}

// Frees v's items on `threads` threads, then v: each item is moved out and
// destroyed on the thread that moved it (a moved-from kernel number holds
// nothing, so what is left frees nothing). The objects lazy numbers point to are
// then freed side by side, not one by one by the thread that ends the run.
template <class T>
void release(std::vector<T>& v, int threads) {
  parallel_chunks(static_cast<int>(v.size()), 4096, threads, [&](int, Chunk r) {
    for (int i = r.begin; i < r.end; ++i) T gone(std::move(v[static_cast<std::size_t>(i)]));
  });
  std::vector<T>().swap(v);
}

// The pages of out's spare capacity that the next `adding` items will fill,
// touched on `threads` threads first (where the capacity is there: callers
// reserve). The kernel zeroes a fresh page when it is first written; touched
// here, side by side, instead of by the one thread that moves items in.
template <class T>
void fault_in_spare(std::vector<T>& out, std::size_t adding, int threads) {
  if (threads < 2 || out.capacity() - out.size() < adding) return;
  unsigned char* begin = reinterpret_cast<unsigned char*>(out.data() + out.size());
  constexpr std::size_t kPage = 4096;
  const int pages = static_cast<int>((adding * sizeof(T) + kPage - 1) / kPage);
  parallel_chunks(pages, 512, threads, [&](int, Chunk r) {   // (512 pages: 2 MiB, a large page)
    for (int p = r.begin; p < r.end; ++p) static_cast<volatile unsigned char*>(begin)[static_cast<std::size_t>(p) * kPage] = 0;
  });
}

// Appends to `out` the items of `chunks` chunks made in parallel, in chunk
// order: fill(k, items) puts chunk k's into `items`, on the thread that runs it.
// Waves of 64 chunks, each appended before the next: at most one wave's items
// are held twice.
template <class T, class Fill>
void parallel_append(std::vector<T>& out, int chunks, int threads, Fill&& fill) {
  const int wave = 64;
  for (int w = 0; w < chunks; w += wave) {
    std::vector<std::vector<T>> made(static_cast<std::size_t>(std::min(wave, chunks - w)));
    parallel_for(static_cast<int>(made.size()), threads, [&](int j) {
      std::vector<T> items;   // (filled here, stored once: the chunks' slots share cache lines)
      fill(w + j, items);
      made[static_cast<std::size_t>(j)] = std::move(items);
    });
    std::size_t adding = 0;
    for (const std::vector<T>& items : made) adding += items.size();
    fault_in_spare(out, adding, threads);
    for (std::vector<T>& items : made) std::move(items.begin(), items.end(), std::back_inserter(out));
  }
}

// A vector of n items made in parallel: make(k, i, item) fills item i (of chunk
// k, chunks of `size`), each default-made on the thread that fills it. (Kernel
// numbers default-made on one thread hold that thread's shared zero: replaced on
// other threads, they would all release it there at once, one reference count
// bouncing between the cores.)
template <class T, class Make>
std::vector<T> parallel_make(int n, int size, int threads, Make&& make) {
  std::vector<T> out;
  out.reserve(static_cast<std::size_t>(n));
  parallel_append(out, chunk_count(n, size), threads, [&](int k, std::vector<T>& items) {
    const Chunk r = chunk(k, n, size);
    items.resize(static_cast<std::size_t>(r.end - r.begin));
    for (int i = r.begin; i < r.end; ++i) make(k, i, items[static_cast<std::size_t>(i - r.begin)]);
  });
  return out;
}

// The i in [0, n) where keep(i), ascending: chunks tested side by side, then
// appended in order.
template <class Keep>
std::vector<int> indices_where(int n, int threads, Keep&& keep) {
  std::vector<int> out;
  const int size = 16384;
  parallel_append(out, chunk_count(n, size), threads, [&](int k, std::vector<int>& found) {
    const Chunk r = chunk(k, n, size);
    for (int i = r.begin; i < r.end; ++i)
      if (keep(i)) found.push_back(i);
  });
  return out;
}

}  // namespace vismap::engine
