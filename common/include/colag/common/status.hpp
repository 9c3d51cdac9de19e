#pragma once
// Errors are values: task code never throws. A Status carries a code and a static message
// (string literal, never allocated); Result<T> carries a value or a Status.
#include <optional>
#include <utility>

namespace colag {

enum class Errc : unsigned char {
  kOk = 0,
  kInvalidArgument,   // malformed input: NaN, wrong size, bad field
  kOutOfRange,        // outside the map, time stamp too old or from the future
  kCapacityExceeded,  // a fixed capacity from limits.hpp would be exceeded
  kNotReady,          // not initialised yet, or no data yet
  kTimeout,
  kUnavailable,       // device or peer not present
  kPermissionDenied,  // e.g. SCHED_FIFO without CAP_SYS_NICE
  kIoError,
  kCorrupt,  // checksum or encoding failure
};

const char* to_string(Errc code);

class [[nodiscard]] Status {
 public:
  constexpr Status() = default;
  constexpr Status(Errc code, const char* message) : code_(code), message_(message) {}
  static constexpr Status ok() { return {}; }

  constexpr bool is_ok() const { return code_ == Errc::kOk; }
  constexpr explicit operator bool() const { return is_ok(); }
  constexpr Errc code() const { return code_; }
  constexpr const char* message() const { return message_; }

 private:
  Errc code_ = Errc::kOk;
  const char* message_ = "";
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Result(Status error) : status_(error) {}       // NOLINT(google-explicit-constructor)

  bool is_ok() const { return value_.has_value(); }
  explicit operator bool() const { return is_ok(); }
  const Status& status() const { return status_; }
  T& value() { return *value_; }
  const T& value() const { return *value_; }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }

 private:
  std::optional<T> value_;
  Status status_;
};

}  // namespace colag
