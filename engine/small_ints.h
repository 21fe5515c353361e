// A short list of ints kept inline: a curve is shared by one or two facets
// almost always, and a million curves with a heap block per list cost a million
// allocations and tens of MB. Up to two values inline, more on the heap; 16
// bytes in all (a std::vector is 24 plus its block).
#pragma once
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <utility>

namespace vismap::engine {

class SmallInts {
 public:
  SmallInts() = default;
  SmallInts(std::initializer_list<int> values) {
    for (int x : values) push_back(x);
  }
  SmallInts(const SmallInts& o) {
    for (int x : o) push_back(x);
  }
  SmallInts(SmallInts&& o) noexcept { take(o); }
  SmallInts& operator=(const SmallInts& o) {
    if (this != &o) {
      clear();
      for (int x : o) push_back(x);
    }
    return *this;
  }
  SmallInts& operator=(SmallInts&& o) noexcept {
    if (this != &o) {
      release();
      take(o);
    }
    return *this;
  }
  ~SmallInts() { release(); }

  void push_back(int x) {
    if (size_ == cap_) grow();
    data()[size_++] = x;
  }
  void clear() { size_ = 0; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  int* data() { return cap_ > kInline ? heap_ : in_; }
  const int* data() const { return cap_ > kInline ? heap_ : in_; }
  int& operator[](std::size_t i) { return data()[i]; }
  int operator[](std::size_t i) const { return data()[i]; }
  int* begin() { return data(); }
  int* end() { return data() + size_; }
  const int* begin() const { return data(); }
  const int* end() const { return data() + size_; }

 private:
  static constexpr std::uint32_t kInline = 2;
  void grow() {
    const std::uint32_t cap = cap_ * 2;
    int* block = new int[cap];
    std::memcpy(block, data(), size_ * sizeof(int));
    release();
    heap_ = block;
    cap_ = cap;
  }
  void release() {
    if (cap_ > kInline) delete[] heap_;
    cap_ = kInline;
  }
  void take(SmallInts& o) {   // (this holds nothing)
    size_ = o.size_;
    cap_ = o.cap_;
    if (o.cap_ > kInline) heap_ = o.heap_;
    else std::memcpy(in_, o.in_, sizeof in_);
    o.cap_ = kInline;
    o.size_ = 0;
  }
  union {
    int in_[kInline];
    int* heap_;
  };
  std::uint32_t size_ = 0, cap_ = kInline;
};

}  // namespace vismap::engine
