#pragma once
// A bounded sequence inside a message: at most N items, `count` of them used, in place (no heap;
// trivially copyable, so the message stays a plain struct). It is what DDS calls
// sequence<T, N>: only the used items cross the wire.
#include <cstddef>
#include <cstdint>

namespace colag::msg {

template <class T, std::size_t N>
struct Sequence {
  static_assert(N > 0 && N <= 0xFFFF, "a sequence's length is a uint16");
  using value_type = T;
  static constexpr std::size_t kCapacity = N;

  std::uint16_t count = 0;  // used items, from items[0]
  T items[N] = {};

  constexpr std::size_t size() const { return count; }
  static constexpr std::size_t capacity() { return N; }
  constexpr bool empty() const { return count == 0; }
  // Any slot within the capacity (a writer fills slots, then sets count).
  constexpr T& operator[](std::size_t i) { return items[i]; }
  constexpr const T& operator[](std::size_t i) const { return items[i]; }
  // The used items.
  constexpr T* begin() { return items; }
  constexpr T* end() { return items + count; }
  constexpr const T* begin() const { return items; }
  constexpr const T* end() const { return items + count; }
  friend bool operator==(const Sequence&, const Sequence&) = default;
};

template <class T>
inline constexpr bool kIsSequence = false;
template <class T, std::size_t N>
inline constexpr bool kIsSequence<Sequence<T, N>> = true;

}  // namespace colag::msg
