// OpenMP's idle threads spin briefly, then sleep, in the executables (linked
// into them, not into the library: how its users' threads wait is theirs to say).
//
// Why: GCC's libgomp, unless told otherwise, lets a thread that has run out of
// work spin up to 300 000 rounds before it sleeps, at the end of each loop and
// between loops. The engine runs hundreds of short parallel loops with serial
// steps between them, so on two threads the idle one spun through 15-25 % of
// the process's CPU time (bunny00 oblique: 1.00 s -> 0.81 s CPU sleeping at
// once, OMP_WAIT_POLICY=passive). Sleeping at once has its own cost: each loop
// then starts by waking the other thread (a futex wake-up, tens of microseconds
// in a virtual machine), and most serial steps between loops are shorter than
// that. 10 000 rounds catch those and little else. Measured against sleeping at
// once, two threads, farm-bench pairs: bunny00 oblique to JSON 0.972x wall for
// 1.05x CPU (libgomp's 300 000 rounds: 0.977x wall for 1.15x CPU), in
// perspective 0.971x wall, the terrain's lines-only drawing 0.989x wall for 1.02x
// CPU. (With more threads than cores libgomp spins far less by itself.)
//
// libgomp reads its settings once, in its own initialiser. Loaded as a shared
// library it is initialised before any code of the executable runs (and a
// .preinit_array function is too early: libc then puts back the environment it
// was started with), so the executables link libgomp's static archive
// (CMakeLists.txt): its initialiser then runs among the executable's, after this
// one, which has the first priority. A policy or spin count the user has set is kept.
#include <cstdlib>

namespace {

[[gnu::constructor(101)]] void prefer_short_openmp_spin() {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
  setenv("GOMP_SPINCOUNT", "10000", /*overwrite=*/0);
}

}  // namespace
