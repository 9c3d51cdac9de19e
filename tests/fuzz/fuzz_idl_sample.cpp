// DDS samples as a robot receives them: CDR bytes (XCDR1, little endian) for one of our topics,
// validated and deserialised by Cyclone DDS's own stream code (what a reader does with a network
// sample), then converted by from_idl(). Invariants: no crash or leak on any bytes; a converted
// message converts back to an IDL sample that converts to the same message.
#include <cstdlib>
#include <cstring>
#include <new>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "colag/platform/dds/convert.hpp"
#include "dds/ddsi/ddsi_cdrstream.h"
#include "fuzz_input.hpp"

namespace {

using namespace colag;
using namespace colag::platform::dds;

constexpr std::uint32_t kXcdr1 = 1;

// Field by field, each leaf by its bytes (NaN != NaN, yet it must come back unchanged). Not the
// struct's bytes: padding is no field, and an assignment need not copy it.
template <class F>
bool same_bits(const F& a, const F& b) {
  if constexpr (std::is_array_v<F>) {
    for (std::size_t i = 0; i < std::extent_v<F>; ++i)
      if (!same_bits(a[i], b[i])) return false;
    return true;
  } else if constexpr (msg::kIsSequence<F>) {
    if (a.count != b.count) return false;
    for (std::size_t i = 0; i < F::kCapacity; ++i)
      if (!same_bits(a.items[i], b.items[i])) return false;
    return true;
  } else if constexpr (msg::HasFields<F>) {
    bool same = true;
    const auto x = msg::Fields<F>::tie(a);
    const auto y = msg::Fields<F>::tie(b);
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      ((same = same && same_bits(std::get<I>(x), std::get<I>(y))), ...);
    }
    (std::make_index_sequence<msg::Fields<F>::kNames.size()>{});
    return same;
  } else {
    static_assert(std::has_unique_object_representations_v<F> || std::is_floating_point_v<F> ||
                  std::is_same_v<F, bool> || std::is_enum_v<F>);
    return std::memcmp(&a, &b, sizeof(F)) == 0;
  }
}

template <class Msg>
void run(const std::uint8_t* data, std::size_t size) {
  const dds_topic_descriptor_t& desc = descriptor<Msg>();
  // Normalising checks (and may byte-swap) in place: work on an aligned copy.
  std::vector<std::uint64_t> buffer((size + 7) / 8 + 1);
  std::memcpy(buffer.data(), data, size);
  std::uint32_t offset = 0;
  if (!dds_stream_normalize_data(reinterpret_cast<char*>(buffer.data()), &offset,
                                 static_cast<std::uint32_t>(size), false, kXcdr1, desc.m_ops)) {
    return;  // Cyclone drops such a sample before any reader sees it
  }
  void* sample = std::calloc(1, desc.m_size);
  dds_istream_t is;
  dds_istream_init(&is, static_cast<std::uint32_t>(size), buffer.data(), kXcdr1);
  dds_stream_read(&is, static_cast<char*>(sample), desc.m_ops);

  using Idl = typename IdlSample<Msg>::Type;
  static_assert(std::is_trivially_destructible_v<Msg>);
  auto* msg = new (std::calloc(1, sizeof(Msg))) Msg;
  auto* again = new (std::calloc(1, sizeof(Msg))) Msg;
  if (from_idl(*static_cast<const Idl*>(sample), *msg)) {
    auto* back = new IdlSample<Msg>;
    to_idl(*msg, *back);
    COLAG_FUZZ_CHECK(from_idl(back->sample, *again));
    COLAG_FUZZ_CHECK(same_bits(*msg, *again));
    delete back;
  }
  std::free(msg);
  std::free(again);
  dds_stream_free_sample(sample, desc.m_ops);
  std::free(sample);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0 || size > (1u << 16)) return 0;
  const auto topic = static_cast<msg::Topic>(data[0] % msg::kTopicCount);
  msg::visit_message_type(topic, [&]<class Msg>() { run<Msg>(data + 1, size - 1); });
  return 0;
}
