#pragma once
// How many bytes a message puts on the wire: its CDR serialisation as DDS sends it (the 4-byte
// encapsulation header, then XCDR1 with each primitive aligned to its size, bounded sequences
// as a uint32 count and the used items only), from the same field list as the IDL mirror. The
// simulator's per-robot traffic counts use it; a DDS test checks it against Cyclone's own
// serializer for every message. RTPS, UDP and IP headers (and DDS Security's) come on top.
#include <cstddef>
#include <type_traits>

#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/sequence.hpp"

namespace colag::msg {

namespace detail {
constexpr std::size_t align_to(std::size_t offset, std::size_t a) {
  return (offset + a - 1) / a * a;
}

// Adds the CDR bytes of `v` at `offset` (from the start of the data, after the header).
template <class F>
constexpr std::size_t cdr_append(std::size_t offset, const F& v) {
  if constexpr (std::is_array_v<F>) {
    for (const auto& e : v)
      offset = cdr_append(offset, e);
    return offset;
  } else if constexpr (std::is_same_v<F, TimePoint>) {
    return align_to(offset, 8) + 8;  // int64 nanoseconds
  } else if constexpr (kIsSequence<F>) {
    offset = align_to(offset, 4) + 4;
    for (const auto& e : v)
      offset = cdr_append(offset, e);
    return offset;
  } else if constexpr (HasFields<F>) {
    for_each_field(v, [&](auto, const auto& field) { offset = cdr_append(offset, field); });
    return offset;
  } else {
    static_assert(std::is_arithmetic_v<F> || std::is_enum_v<F>, "a field CDR cannot carry");
    return align_to(offset, sizeof(F)) + sizeof(F);
  }
}
}  // namespace detail

inline constexpr std::size_t kCdrHeaderBytes = 4;

template <class Msg>
constexpr std::size_t wire_bytes(const Msg& m) {
  return kCdrHeaderBytes + detail::cdr_append(0, m);
}

}  // namespace colag::msg
