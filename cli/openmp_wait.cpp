// OpenMP's idle threads sleep instead of spinning, in the executables (linked
// into them, not into the library: how its users' threads wait is theirs to say).
//
// Why: GCC's libgomp, unless told otherwise, lets a thread that has run out of
// work spin for a while (up to 300 000 rounds) before it sleeps, at the end of
// each loop and between loops. The engine runs hundreds of short parallel loops
// with serial steps between them, so on two threads the idle one spun through
// 15-25 % of the process's CPU time (bunny00 oblique: 1.00 s -> 0.81 s CPU with
// OMP_WAIT_POLICY=passive; the terrain lines-only: 5.1 s -> 4.2 s; the bunny
// close-up 1.67 s -> 1.31 s), for no wall time gained: the waits are long beside
// a sleeping thread's wake-up (the same wall time or a little less: the
// spinning thread took a core from the writer's or the kernel's work).
//
// libgomp reads OMP_WAIT_POLICY once, in its own initialiser. Loaded as a
// shared library it is initialised before any code of the executable runs
// (and a .preinit_array function is too early: libc then puts back the
// environment it was started with), so the executables link libgomp's static
// archive (CMakeLists.txt): its initialiser then runs among the executable's,
// after this one, which has the first priority. A policy the user has set is kept.
#include <cstdlib>

namespace {

[[gnu::constructor(101)]] void prefer_passive_openmp_wait() { setenv("OMP_WAIT_POLICY", "passive", /*overwrite=*/0); }

}  // namespace
