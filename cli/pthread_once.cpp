// pthread_once without a system call when nobody waits, for the executables
// (linked into them, not into the library: a library must not replace its
// users' libc functions).
//
// Why: CGAL's lazy numbers compute an exact value under std::call_once, which
// is pthread_once; glibc's ends every first run with a futex wake, a system call
// even when no thread waits. A map makes an exact value for every point it
// writes: 1.1 M system calls for 36 views of the city (5 % of the run's CPU
// time), 30 k for one bunny. This one wakes only where a thread has said it waits.
//
// States of the control word (PTHREAD_ONCE_INIT is 0): new; running; running
// with a waiter (who sleeps on the word while it holds that value); done.
#include <pthread.h>
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <climits>

namespace {

enum : int { kNew = 0, kRunning = 1, kWaited = 2, kDone = 3 };

void futex(int* word, int op, int value) {
  syscall(SYS_futex, word, op | FUTEX_PRIVATE_FLAG, value, nullptr, nullptr, 0);
}

}  // namespace

// (The test finds the replacement linked by this name.)
extern "C" const int vismap_pthread_once_replaced = 1;

extern "C" int pthread_once(pthread_once_t* control, void (*init)(void)) {
  static_assert(sizeof(pthread_once_t) == sizeof(int), "a control word is an int (Linux)");
  int* word = reinterpret_cast<int*>(control);
  std::atomic_ref<int> state(*word);
  for (;;) {
    int s = state.load(std::memory_order_acquire);
    if (s == kDone) return 0;
    if (s == kNew) {
      if (!state.compare_exchange_strong(s, kRunning, std::memory_order_acquire)) continue;
      try {
        init();
      } catch (...) {   // (std::call_once: another call runs it again)
        if (state.exchange(kNew, std::memory_order_acq_rel) == kWaited) futex(word, FUTEX_WAKE, INT_MAX);
        throw;
      }
      if (state.exchange(kDone, std::memory_order_acq_rel) == kWaited) futex(word, FUTEX_WAKE, INT_MAX);
      return 0;
    }
    // Running on another thread: say so, and sleep until it is done (or failed).
    if (s == kRunning && !state.compare_exchange_strong(s, kWaited, std::memory_order_acquire)) continue;
    futex(word, FUTEX_WAIT, kWaited);
  }
}
