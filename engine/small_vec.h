// A short list kept inline: an edge piece or a curve is shared by one or two
// facets almost always, and a million of them with a heap block per list cost a
// million allocations and tens of MB. Up to N values inline, more on the heap
// (T trivially copyable); SmallInts is 16 bytes in all (a std::vector is 24
// plus its block).
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <type_traits>
#include <utility>

namespace vismap::engine {

template <class T, std::uint32_t N>
class SmallVec {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  SmallVec() = default;
  SmallVec(std::initializer_list<T> values) {
    for (const T& x : values) push_back(x);
  }
  template <std::input_iterator It>
  SmallVec(It first, It last) {
    for (; first != last; ++first) push_back(*first);
  }
  SmallVec(std::size_t n, const T& x) {
    for (std::size_t i = 0; i < n; ++i) push_back(x);
  }
  SmallVec(const SmallVec& o) {
    for (const T& x : o) push_back(x);
  }
  SmallVec(SmallVec&& o) noexcept { take(o); }
  SmallVec& operator=(const SmallVec& o) {
    if (this != &o) {
      clear();
      for (const T& x : o) push_back(x);
    }
    return *this;
  }
  SmallVec& operator=(SmallVec&& o) noexcept {
    if (this != &o) {
      release();
      take(o);
    }
    return *this;
  }
  ~SmallVec() { release(); }

  void push_back(const T& x) {
    if (size_ == cap_) grow();
    data()[size_++] = x;
  }
  void clear() { size_ = 0; }
  void truncate(std::size_t n) { size_ = static_cast<std::uint32_t>(n); }   // (n <= size())
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T* data() { return cap_ > kInline ? heap_ : in_; }
  const T* data() const { return cap_ > kInline ? heap_ : in_; }
  T& operator[](std::size_t i) { return data()[i]; }
  const T& operator[](std::size_t i) const { return data()[i]; }
  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }

 private:
  static constexpr std::uint32_t kInline = N;
  void grow() {
    const std::uint32_t cap = cap_ * 2;
    T* block = new T[cap];
    std::memcpy(static_cast<void*>(block), data(), size_ * sizeof(T));
    release();
    heap_ = block;
    cap_ = cap;
  }
  void release() {
    if (cap_ > kInline) delete[] heap_;
    cap_ = kInline;
  }
  void take(SmallVec& o) {   // (this holds nothing)
    size_ = o.size_;
    cap_ = o.cap_;
    if (o.cap_ > kInline) heap_ = o.heap_;
    else std::memcpy(in_, o.in_, sizeof in_);
    o.cap_ = kInline;
    o.size_ = 0;
  }
  union {
    T in_[kInline];
    T* heap_;
  };
  std::uint32_t size_ = 0, cap_ = kInline;
};

template <class T, std::uint32_t N>
bool operator==(const SmallVec<T, N>& a, const SmallVec<T, N>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end());
}
template <class T, std::uint32_t N>
bool operator<(const SmallVec<T, N>& a, const SmallVec<T, N>& b) {   // lexicographic
  return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end());
}

using SmallInts = SmallVec<int, 2>;

}  // namespace vismap::engine
