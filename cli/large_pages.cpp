// mimalloc takes its memory from the kernel in 2 MiB pages where the kernel
// lends them (transparent huge pages), in the executables that link mimalloc
// (not in the library: its users' allocator is theirs to set).
//
// Why: the engine fills tens of megabytes of fresh memory per view (bunny00:
// ~72 MB; the 10^6-triangle terrain: ~860 MB), and on the shared machines here
// the kernel takes ~8 us per 4 KiB page fault: 18 000 faults were 0.15 s of the
// bunny's 0.52 s, and those on the serial steps kept a second thread waiting.
// In 2 MiB pages the same memory takes ~500 faults; fewer TLB misses too.
// Measured, one thread, bunny00 oblique to JSON: 0.56 s -> 0.35 s wall; the
// terrain's full map 10.5 s -> 5.8 s, its peak 831 -> 863 MB (pages are
// committed whole).
//
// When: before any library's initialiser, from .preinit_array. libstdc++'s
// initialiser already allocates, and the segment that allocation opens (32 MiB,
// where most small objects of the main thread then live) would be mapped in
// small pages. mimalloc's own initialiser, which runs later, keeps an option
// set through its interface. A choice the user made (MIMALLOC_LARGE_OS_PAGES,
// read here from the environment the process was started with) is kept.
#include <cstring>

#include <mimalloc.h>

namespace {

void prefer_large_pages(int, char**, char** envp) {
  constexpr char kUsersChoice[] = "MIMALLOC_LARGE_OS_PAGES=";
  for (char** e = envp; *e != nullptr; ++e)
    if (std::strncmp(*e, kUsersChoice, sizeof kUsersChoice - 1) == 0) return;
  mi_option_enable(mi_option_large_os_pages);
  // Each OpenMP thread's first segment too (mimalloc commits it lazily, in small
  // pages, unless told not to delay: a thread's untouched pages still cost nothing).
  mi_option_set(mi_option_eager_commit_delay, 0);
}

[[gnu::section(".preinit_array"), gnu::used]] void (*const prefer_large_pages_early)(int, char**, char**) =
    prefer_large_pages;

}  // namespace
