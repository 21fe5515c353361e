#include "engine/parallel.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

namespace vismap::engine {

int usable_cores() {
#ifdef _OPENMP
  int cores = std::max(1, omp_get_num_procs());   // (the CPUs the process may run on)
#else
  int cores = 1;
#endif
  // cgroup v2: "max PERIOD" or "QUOTA PERIOD" (microseconds of CPU per period).
  std::ifstream in("/sys/fs/cgroup/cpu.max");
  std::string quota;
  double period = 0;
  if (in >> quota >> period && quota != "max" && period > 0) {
    char* end = nullptr;
    const double q = std::strtod(quota.c_str(), &end) / period;
    if (end != quota.c_str() && q > 0) cores = std::min(cores, std::max(1, static_cast<int>(std::ceil(q))));
  }
  return cores;
}

}  // namespace vismap::engine
