#pragma once
// Message struct <-> IDL sample conversion, both ways, for every message: generic over the
// message's field list (msg::Fields), zipped with its generated C mirror field by field (the IDL
// is generated from the same list, in the same order: colag_idl_gen). to_idl() fills an
// IdlSample that may borrow the message's byte sequences (keep the message alive while the
// sample is used); from_idl() rejects what the message struct cannot hold (a sequence longer
// than its bound, an enum value past its last) and leaves semantic checks (NaN, stale stamps) to
// the receiving task. Neither allocates.
#include <array>
#include <cstdint>
#include <cstring>
#include <tuple>
#include <type_traits>

#include "colag/common/status.hpp"
#include "colag/msg/topics.hpp"
#include "colag_msgs_bindings.hpp"

namespace colag::platform::dds {

namespace detail {

// The C element type of a generated sequence struct.
template <class CSeq>
using SeqElement = std::remove_pointer_t<decltype(CSeq{}._buffer)>;

// A sequence of structs is converted into storage beside the sample; a sequence of numbers is
// lent from the message as it is.
template <class F, class C>
struct Scratch {};
template <class T, std::size_t N, class C>
requires msg::HasFields<T>
struct Scratch<msg::Sequence<T, N>, C> {
  std::array<SeqElement<C>, N> items{};
};

// The type of field I of S, a struct with the fields of Msg (Msg itself, or its C mirror).
template <class Msg, class S, std::size_t I>
using FieldType = std::remove_cvref_t<
    std::tuple_element_t<I, decltype(msg::Fields<Msg>::tie(std::declval<S&>()))>>;

template <class Msg, class C, class Seq>
struct ScratchTuple;
template <class Msg, class C, std::size_t... I>
struct ScratchTuple<Msg, C, std::index_sequence<I...>> {
  using Type = std::tuple<Scratch<FieldType<Msg, Msg, I>, FieldType<Msg, C, I>>...>;
};

}  // namespace detail

// A sample plus the storage its sequences of structs point into; not copyable (it points into
// itself).
template <class Msg>
struct IdlSample {
  using Type = typename IdlBinding<Msg>::Type;
  IdlSample() = default;
  IdlSample(const IdlSample&) = delete;
  IdlSample& operator=(const IdlSample&) = delete;
  Type sample{};
  typename detail::ScratchTuple<
      Msg, Type, std::make_index_sequence<msg::Fields<Msg>::kNames.size()>>::Type scratch{};
};

namespace detail {

template <class F, class C>
void put(const F& a, C& b);
template <class F, class C>
Status take(const C& b, F& a);
template <class F, class C, class S, std::size_t I>
void put_field(const F& a, C& b, S* scratch, std::integral_constant<std::size_t, I>);

// Struct to struct, field by field.
template <class F, class C, class S = std::tuple<>>
void put_fields(const F& a, C& b, S* scratch = nullptr) {
  auto from = msg::Fields<F>::tie(a);
  auto to = msg::Fields<F>::tie(b);
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (put_field(std::get<I>(from), std::get<I>(to), scratch,
               std::integral_constant<std::size_t, I>{}),
     ...);
  }
  (std::make_index_sequence<msg::Fields<F>::kNames.size()>{});
}

template <class F, class C, class S, std::size_t I>
void put_field(const F& a, C& b, S* scratch, std::integral_constant<std::size_t, I>) {
  if constexpr (msg::kIsSequence<F>) {
    using T = typename F::value_type;
    const std::uint32_t n = a.count < F::kCapacity ? a.count : F::kCapacity;
    b._maximum = static_cast<std::uint32_t>(F::kCapacity);
    b._length = n;
    b._release = false;
    if constexpr (std::is_same_v<T, SeqElement<C>>) {
      b._buffer = const_cast<T*>(a.items);  // lent: DDS only reads it
    } else {
      auto& items = std::get<I>(*scratch).items;
      for (std::uint32_t i = 0; i < n; ++i)
        put(a.items[i], items[i]);
      b._buffer = items.data();
    }
  } else {
    put(a, b);
  }
}

template <class F, class C>
void put(const F& a, C& b) {
  if constexpr (std::is_array_v<F>) {
    for (std::size_t i = 0; i < std::extent_v<F>; ++i)
      put(a[i], b[i]);
  } else if constexpr (std::is_same_v<F, TimePoint>) {
    b = to_nanoseconds(a);
  } else if constexpr (std::is_enum_v<F>) {
    b = static_cast<C>(a);
  } else if constexpr (msg::HasFields<F>) {
    put_fields(a, b);
  } else {
    static_assert(std::is_same_v<F, C>, "the IDL mirror has another type for this field");
    b = a;
  }
}

template <class F, class C>
Status take(const C& b, F& a) {
  if constexpr (std::is_array_v<F>) {
    for (std::size_t i = 0; i < std::extent_v<F>; ++i) {
      if (Status s = take(b[i], a[i]); !s) return s;
    }
  } else if constexpr (std::is_same_v<F, TimePoint>) {
    a = time_at_nanoseconds(b);
  } else if constexpr (std::is_same_v<F, bool>) {
    // The wire's byte, read as a byte: a bool holding another value than 0 or 1 is undefined
    // behaviour to read (the fuzzer found one surviving Cyclone's checks).
    static_assert(sizeof(C) == 1);
    unsigned char raw = 0;
    std::memcpy(&raw, &b, 1);
    if (raw > 1) return {Errc::kInvalidArgument, "DDS sample: a boolean neither 0 nor 1"};
    a = raw == 1;
  } else if constexpr (std::is_enum_v<F>) {
    using U = std::underlying_type_t<F>;
    if (b > static_cast<U>(msg::EnumRange<F>::kLast))
      return {Errc::kInvalidArgument, "DDS sample: an enum value past its last"};
    a = static_cast<F>(b);
  } else if constexpr (msg::kIsSequence<F>) {
    using T = typename F::value_type;
    if (b._length > F::kCapacity || (b._length > 0 && b._buffer == nullptr))
      return {Errc::kInvalidArgument, "DDS sample: a sequence longer than its bound"};
    for (std::uint32_t i = 0; i < F::kCapacity; ++i) {
      if (i < b._length) {
        if (Status s = take(b._buffer[i], a.items[i]); !s) return s;
      } else {
        a.items[i] = T{};
      }
    }
    a.count = static_cast<std::uint16_t>(b._length);
  } else if constexpr (msg::HasFields<F>) {
    auto from = msg::Fields<F>::tie(b);
    auto to = msg::Fields<F>::tie(a);
    Status s;
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      ((s = s ? take(std::get<I>(from), std::get<I>(to)) : s), ...);
    }
    (std::make_index_sequence<msg::Fields<F>::kNames.size()>{});
    return s;
  } else {
    static_assert(std::is_same_v<F, C>, "the IDL mirror has another type for this field");
    a = b;
  }
  return Status::ok();
}

}  // namespace detail

template <class Msg>
void to_idl(const Msg& in, IdlSample<Msg>& out) {
  detail::put_fields(in, out.sample, &out.scratch);
}

template <class Msg>
Status from_idl(const typename IdlBinding<Msg>::Type& in, Msg& out) {
  return detail::take(in, out);
}

// The generated type descriptor of each message's IDL mirror.
template <class Msg>
const dds_topic_descriptor_t& descriptor() {
  return IdlBinding<Msg>::descriptor();
}

}  // namespace colag::platform::dds
