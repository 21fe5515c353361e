// How CGAL is configured for the engine; CMake force-includes this file ahead of
// every translation unit of vismap_core and its users, so every unit that
// instantiates CGAL sees the same settings.
//
// 1. Thread-safe (CGAL_HAS_THREADS, CGAL's default): Franklin's engine runs loops
//    on several threads (engine/parallel.h) over lazy numbers they share. The
//    price on one thread, 10-14% of the CPU time (docs/how-it-works.md, Threads): a
//    std::call_once per first exact evaluation, and reference counts that are
//    out-of-line calls asking glibc whether the process is still single-threaded
//    (__libc_single_threaded; they become atomic once a second thread exists).
//
// 2. How often the exact kernel's floating-point filter could not settle a question.
// CGAL reports each filtered predicate (and each lazy comparison) through its
// profiling macros: a call, and a "branch" when the interval answer was uncertain
// and exact arithmetic had to decide. We define those two macros to bump plain
// counters, so the stats can say how much exact work a scene needed. (CGAL's
// static filters use the same two macros the other way round: there the branch
// is the static filter's success, and its failure goes on to a filtered
// predicate that counts the call again. There a success counts as one call and
// nothing else does.)
#pragma once
#define VISMAP_EXACT_CONFIG_H
#include <CGAL/Profile_counter.h>

#include <cstdint>
#include <string_view>

namespace vismap::exact {

struct FilterCounts {
  std::int64_t calls = 0;   // filtered predicates and comparisons run
  std::int64_t exact = 0;   // of those, decided by exact arithmetic
};
inline thread_local FilterCounts filter_counts;   // per thread; parallel_for sums them

constexpr bool in_static_filter(std::string_view file) { return file.find("Static_filters") != file.npos; }

}  // namespace vismap::exact

#undef CGAL_BRANCH_PROFILER
#undef CGAL_BRANCH_PROFILER_BRANCH
#define CGAL_BRANCH_PROFILER(Y, NAME) \
  if constexpr (!::vismap::exact::in_static_filter(__FILE__)) ++::vismap::exact::filter_counts.calls;
#define CGAL_BRANCH_PROFILER_BRANCH(NAME)                                 \
  if constexpr (::vismap::exact::in_static_filter(__FILE__))              \
    ++::vismap::exact::filter_counts.calls;                               \
  else                                                                    \
    ++::vismap::exact::filter_counts.exact;
