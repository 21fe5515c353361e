// The process's CPU time in seconds: what the benchmark programs measure (the
// machines are shared, so wall time is noisier).
#pragma once
#include <time.h>

namespace vismap::bench {

inline double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace vismap::bench
