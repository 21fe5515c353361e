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
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>

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

// Memory that the engine frees in large blocks is used again by the next large
// block, not given back to the kernel and asked for anew, in the executables.
//
// Why: mimalloc returns a block of more than half its 32 MiB segments (a
// vector of a million facets or pieces) to the kernel as soon as it is freed,
// and the next such block comes in fresh pages, which the kernel zeroes again
// (on the shared machines here, through the host: 0.2-3 ms per 2 MiB page).
// The 10^6-triangle terrain's full map had 1.66 GB of fresh pages zeroed for
// an 0.85 GB peak, its lines-only drawing 0.63 GB for 0.47 GB. Memory that
// mimalloc manages as an arena (address space only, reserved once; the kernel
// lends a page where it is first written) is kept and reused instead: 0.89 GB
// and 0.47 GB zeroed (peaks 0.90 and 0.49 GB: freed blocks do not always fit).
//
// How: the machine's physical memory as address space (nothing is committed:
// MAP_NORESERVE; not where the kernel counts every mapping against its limit,
// vm.overcommit_memory = 2), aligned for mimalloc's segments, in 2 MiB pages
// where large pages are chosen, handed to mimalloc after its initialiser ran.
// Beyond it mimalloc asks the kernel as before. A reservation the user chose
// (MIMALLOC_RESERVE_OS_MEMORY) is kept as the only one.
bool counts_every_mapping() {
  std::ifstream mode("/proc/sys/vm/overcommit_memory");
  int m = 0;
  return (mode >> m) && m == 2;
}

[[gnu::constructor(102)]] void reserve_memory_to_reuse() {
  if (std::getenv("MIMALLOC_RESERVE_OS_MEMORY") != nullptr || counts_every_mapping()) return;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return;
  constexpr std::uintptr_t kAlign = std::uintptr_t{64} << 20;   // (a multiple of mimalloc's segment size)
  const std::size_t size = static_cast<std::size_t>(pages) * static_cast<std::size_t>(page) / kAlign * kAlign;
  if (size < kAlign) return;
  void* raw = mmap(nullptr, size + kAlign, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (raw == MAP_FAILED) return;
  // The aligned part kept, the rest given back (the tail is never empty).
  const auto at = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t start = (at + kAlign - 1) / kAlign * kAlign, end = start + size;
  if (start > at) munmap(raw, start - at);
  munmap(reinterpret_cast<void*>(end), at + size + kAlign - end);
  void* arena = reinterpret_cast<void*>(start);
  if (mi_option_is_enabled(mi_option_large_os_pages)) madvise(arena, size, MADV_HUGEPAGE);
  if (!mi_manage_os_memory(arena, size, /*is_committed=*/true, /*is_large=*/false, /*is_zero=*/true, /*numa_node=*/-1))
    munmap(arena, size);
}

}  // namespace
