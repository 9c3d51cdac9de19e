#pragma once
// A FIFO with a compile-time capacity and no heap. Index 0 is the oldest element.
// Two ways to add: try_push (refuses when full) and push_overwrite (drops the oldest),
// so a caller always decides explicitly what happens on overflow.
#include <array>
#include <cassert>
#include <cstddef>
#include <type_traits>

namespace colag {

template <class T, std::size_t N>
class RingBuffer {
  static_assert(N > 0);

 public:
  constexpr std::size_t size() const { return size_; }
  static constexpr std::size_t capacity() { return N; }
  constexpr bool empty() const { return size_ == 0; }
  constexpr bool full() const { return size_ == N; }
  constexpr void clear() { head_ = size_ = 0; }

  [[nodiscard]] constexpr bool try_push(const T& value) {
    if (full()) return false;
    items_[(head_ + size_) % N] = value;
    ++size_;
    return true;
  }
  // Returns true if the oldest element had to be dropped to make room.
  constexpr bool push_overwrite(const T& value) {
    const bool dropped = full();
    if (dropped) pop_front();
    items_[(head_ + size_) % N] = value;
    ++size_;
    return dropped;
  }
  constexpr void pop_front() {
    assert(!empty());
    head_ = (head_ + 1) % N;
    --size_;
  }
  [[nodiscard]] constexpr bool pop_front(T& out) {
    if (empty()) return false;
    out = items_[head_];
    pop_front();
    return true;
  }

  constexpr T& operator[](std::size_t i) {
    assert(i < size_);
    return items_[(head_ + i) % N];
  }
  constexpr const T& operator[](std::size_t i) const {
    assert(i < size_);
    return items_[(head_ + i) % N];
  }
  constexpr T& front() { return (*this)[0]; }
  constexpr T& back() { return (*this)[size_ - 1]; }
  constexpr const T& front() const { return (*this)[0]; }
  constexpr const T& back() const { return (*this)[size_ - 1]; }

 private:
  std::array<T, N> items_{};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace colag
