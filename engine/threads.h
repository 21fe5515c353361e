// How many threads a run uses (engine/parallel.h runs them). Light: the CLI
// includes it.
#pragma once
#include <cstddef>

namespace vismap::engine {

// The cores this process may use: those it may run on, fewer where a cgroup's
// CPU quota (a container's --cpus) allows less (more threads than that would
// only wait for each other).
int usable_cores();

// The number of threads a run uses: `asked` if positive, else every usable core,
// but one for a scene of fewer than 8192 faces (starting the threads and
// counting references atomically cost more there than the threads gain: the
// elephant's 5 558 faces took 16% longer on two threads than on one).
constexpr std::size_t kFewFaces = 8192;   // (below: one thread by default)
inline int thread_count(int asked, std::size_t faces) {
  if (asked > 0) return asked;
  return faces < kFewFaces ? 1 : usable_cores();
}

}  // namespace vismap::engine
