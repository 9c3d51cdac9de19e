#pragma once
// A message's fields, listed once beside its struct: COLAG_MESSAGE_FIELDS(Type, a, b, c) right
// after `struct Type { ... };` gives generic code (the DDS conversions, the IDL generator, tests)
// the fields' names and, for any struct with the same fields in the same order (the message, or
// its DDS mirror), references to them: msg::Fields<Type>::tie(s). The list is checked where it
// is written: every field of the struct, each once, in declaration order, or it does not compile.
#include <array>
#include <cstddef>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

namespace colag::msg {

// Specialised for each message (and each struct inside one) by COLAG_MESSAGE_FIELDS.
template <class T>
struct Fields;

template <class T>
concept HasFields = requires {
  Fields<T>::kNames;
};

// The range of an enum carried in a message: specialise with the last enumerator. A receiver
// rejects a value above it (a newer peer's, or a corrupt one); an enum without it does not
// compile into a message.
template <class E>
struct EnumRange;

// Calls f(name, field) for every field of `m`, in order.
template <class T, class F>
constexpr void for_each_field(T& m, F&& f) {
  using Plain = std::remove_const_t<T>;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    auto refs = Fields<Plain>::tie(m);
    (f(Fields<Plain>::kNames[I], std::get<I>(refs)), ...);
  }
  (std::make_index_sequence<Fields<Plain>::kNames.size()>{});
}

namespace detail {
constexpr bool strictly_increasing(const std::size_t* v, std::size_t n) {
  for (std::size_t i = 1; i < n; ++i)
    if (!(v[i - 1] < v[i])) return false;
  return true;
}
}  // namespace detail

}  // namespace colag::msg

// Applies m(arg, x) to every further argument x (up to 64; C++20 __VA_OPT__ recursion).
#define COLAG_MSG_PARENS ()
#define COLAG_MSG_EXPAND(...) COLAG_MSG_EXPAND3(COLAG_MSG_EXPAND3(COLAG_MSG_EXPAND3(__VA_ARGS__)))
#define COLAG_MSG_EXPAND3(...) COLAG_MSG_EXPAND2(COLAG_MSG_EXPAND2(COLAG_MSG_EXPAND2(__VA_ARGS__)))
#define COLAG_MSG_EXPAND2(...) COLAG_MSG_EXPAND1(COLAG_MSG_EXPAND1(COLAG_MSG_EXPAND1(__VA_ARGS__)))
#define COLAG_MSG_EXPAND1(...) __VA_ARGS__
#define COLAG_MSG_FOR_EACH(m, arg, ...) \
  __VA_OPT__(COLAG_MSG_EXPAND(COLAG_MSG_FOR_EACH_STEP(m, arg, __VA_ARGS__)))
#define COLAG_MSG_FOR_EACH_STEP(m, arg, x, ...) \
  m(arg, x) __VA_OPT__(COLAG_MSG_FOR_EACH_AGAIN COLAG_MSG_PARENS(m, arg, __VA_ARGS__))
#define COLAG_MSG_FOR_EACH_AGAIN() COLAG_MSG_FOR_EACH_STEP
#define COLAG_MSG_NAME(T, x) #x,
#define COLAG_MSG_OFFSET(T, x) offsetof(T, x),

// In namespace colag::msg, after the struct: the struct's fields in declaration order.
#define COLAG_MESSAGE_FIELDS(T, ...)                                                               \
  template <>                                                                                      \
  struct Fields<T> {                                                                               \
    static constexpr std::string_view kType = #T;                                                  \
    static constexpr auto kNames =                                                                 \
        std::to_array<std::string_view>({COLAG_MSG_FOR_EACH(COLAG_MSG_NAME, T, __VA_ARGS__)});     \
    /* T, or any struct with the same fields in the same order (its DDS mirror). */                \
    template <class S>                                                                             \
    static constexpr auto tie(S& s) {                                                              \
      auto& [__VA_ARGS__] = s;                                                                     \
      return std::tie(__VA_ARGS__);                                                                \
    }                                                                                              \
  };                                                                                               \
  static_assert(                                                                                   \
      std::tuple_size_v<decltype(Fields<T>::tie(std::declval<T&>()))> == Fields<T>::kNames.size(), \
      #T ": COLAG_MESSAGE_FIELDS must list every field");                                          \
  static_assert(                                                                                   \
      [] {                                                                                         \
        constexpr std::size_t offsets[] = {COLAG_MSG_FOR_EACH(COLAG_MSG_OFFSET, T, __VA_ARGS__)};  \
        return detail::strictly_increasing(offsets, std::size(offsets));                           \
      }(),                                                                                         \
      #T ": COLAG_MESSAGE_FIELDS must list the fields in declaration order")
