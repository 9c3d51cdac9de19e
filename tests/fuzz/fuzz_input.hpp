#pragma once
// Reading a fuzzer's input as a little-endian byte stream: past the end every read yields 0, so a
// fuzzer never reads out of bounds and short inputs still exercise the code.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace colag::fuzz {

class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::uint16_t u16() { return static_cast<std::uint16_t>(u8() | (u8() << 8)); }
  std::uint32_t u32() { return u16() | (static_cast<std::uint32_t>(u16()) << 16); }
  std::size_t remaining() const { return size_ - pos_; }
  const std::uint8_t* rest() const { return data_ + pos_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// A broken invariant: abort so that libFuzzer records the input as a crash.
#define COLAG_FUZZ_CHECK(cond)                                                            \
  do {                                                                                    \
    if (!(cond)) {                                                                        \
      std::fprintf(stderr, "fuzz check failed: %s (%s:%d)\n", #cond, __FILE__, __LINE__); \
      std::abort();                                                                       \
    }                                                                                     \
  } while (0)

}  // namespace colag::fuzz
