// The vertex images of a screen scene, by place: slots that facets and curves
// point at from the start, each image made in its slot when it is first needed.
// A lines-only drawing needs the images of the few vertices near its drawn lines
// (on a 10^6-triangle terrain, a few per cent of them): the others are never
// made, and their slots, memory the system hands out zeroed, are never touched
// (the images were 150 MB there, each three lazy numbers and a point).
#pragma once
#include <cstddef>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

#include "engine/exact_kernel.h"
#include "engine/parallel.h"

namespace vismap::engine {
using namespace vismap::exact;
VISMAP_KERNEL_BEGIN

// An image's intervals as its numbers have them when it is made (what a box of
// it, or a filter, reads), kept where the images themselves are left for later.
struct ImageBounds {
  Interval x, y, z;
};

class ImageTable {
 public:
  ImageTable() = default;
  explicit ImageTable(std::size_t n) : n_(n), made_(n, 0) {
    // (calloc: slots never made stay untouched pages, and hold null handles, so
    // that reading one is a crash, not a wrong value.)
    if (n > 0 && !(slots_ = static_cast<P3*>(std::calloc(n, sizeof(P3))))) throw std::bad_alloc();
  }
  ImageTable(ImageTable&& o) noexcept { swap(o); }
  ImageTable& operator=(ImageTable&& o) noexcept {
    ImageTable gone(std::move(*this));
    swap(o);
    return *this;
  }
  ~ImageTable() { clear(1); }

  std::size_t size() const { return n_; }
  const P3* data() const { return slots_; }
  const P3& operator[](std::size_t i) const { return slots_[i]; }
  bool made(std::size_t i) const { return made_[i] != 0; }
  // Makes slot i's image (once: it must not be made yet). Different slots may be
  // made on different threads at once.
  void make(std::size_t i, P3 image) {
    new (slots_ + i) P3(std::move(image));
    made_[i] = 1;
  }
  // Frees every image made (on `threads` threads), then the slots.
  void clear(int threads) {
    if (!slots_) return;
    parallel_chunks(static_cast<int>(n_), 4096, threads, [&](int, Chunk r) {
      for (int i = r.begin; i < r.end; ++i)
        if (made_[static_cast<std::size_t>(i)]) slots_[i].~P3();
    });
    std::free(slots_);
    slots_ = nullptr;
    n_ = 0;
    std::vector<char>().swap(made_);
  }

 private:
  void swap(ImageTable& o) noexcept {
    std::swap(slots_, o.slots_);
    std::swap(n_, o.n_);
    std::swap(made_, o.made_);
  }
  P3* slots_ = nullptr;
  std::size_t n_ = 0;
  std::vector<char> made_;
};

// (As release() frees a vector's items side by side.)
inline void release(ImageTable& t, int threads) { t.clear(threads); }

VISMAP_KERNEL_END
}  // namespace vismap::engine
