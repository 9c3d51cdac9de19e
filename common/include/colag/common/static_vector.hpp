#pragma once
// A vector with a compile-time capacity and no heap. Elements live in a std::array, so T must
// be default-constructible; slots past size() hold default values. Full => push_back returns
// false (never throws, never reallocates).
#include <array>
#include <cassert>
#include <cstddef>
#include <type_traits>

namespace colag {

template <class T, std::size_t N>
class StaticVector {
 public:
  using value_type = T;
  using iterator = T*;
  using const_iterator = const T*;

  constexpr std::size_t size() const { return size_; }
  static constexpr std::size_t capacity() { return N; }
  constexpr bool empty() const { return size_ == 0; }
  constexpr bool full() const { return size_ == N; }

  [[nodiscard]] constexpr bool push_back(const T& value) {
    if (size_ == N) return false;
    items_[size_++] = value;
    return true;
  }
  constexpr void pop_back() {
    assert(size_ > 0);
    items_[--size_] = T{};
  }
  constexpr void clear() { size_ = 0; }
  // Shrinks or grows (new slots default-valued); returns false if n > capacity.
  [[nodiscard]] constexpr bool resize(std::size_t n) {
    if (n > N) return false;
    for (std::size_t i = size_; i < n; ++i)
      items_[i] = T{};
    size_ = n;
    return true;
  }
  // Puts `value` at position i (<= size), the elements from i on one place later; false if full.
  [[nodiscard]] constexpr bool insert_at(std::size_t i, const T& value) {
    assert(i <= size_);
    if (size_ == N) return false;
    for (std::size_t k = size_; k > i; --k)
      items_[k] = items_[k - 1];
    items_[i] = value;
    ++size_;
    return true;
  }
  // Removes element i, the elements after it one place earlier (order kept).
  constexpr void erase_at(std::size_t i) {
    assert(i < size_);
    for (std::size_t k = i; k + 1 < size_; ++k)
      items_[k] = items_[k + 1];
    pop_back();
  }
  // Removes element i by moving the last one into its place (O(1), order not kept).
  constexpr void swap_remove(std::size_t i) {
    assert(i < size_);
    items_[i] = items_[size_ - 1];
    pop_back();
  }

  constexpr T& operator[](std::size_t i) {
    assert(i < size_);
    return items_[i];
  }
  constexpr const T& operator[](std::size_t i) const {
    assert(i < size_);
    return items_[i];
  }
  constexpr T& front() { return (*this)[0]; }
  constexpr T& back() { return (*this)[size_ - 1]; }
  constexpr const T& front() const { return (*this)[0]; }
  constexpr const T& back() const { return (*this)[size_ - 1]; }
  constexpr T* data() { return items_.data(); }
  constexpr const T* data() const { return items_.data(); }
  constexpr iterator begin() { return items_.data(); }
  constexpr iterator end() { return items_.data() + size_; }
  constexpr const_iterator begin() const { return items_.data(); }
  constexpr const_iterator end() const { return items_.data() + size_; }

 private:
  std::array<T, N> items_{};
  std::size_t size_ = 0;
};

}  // namespace colag
