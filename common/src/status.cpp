#include "colag/common/status.hpp"

namespace colag {

const char* to_string(Errc code) {
  switch (code) {
    case Errc::kOk:
      return "ok";
    case Errc::kInvalidArgument:
      return "invalid argument";
    case Errc::kOutOfRange:
      return "out of range";
    case Errc::kCapacityExceeded:
      return "capacity exceeded";
    case Errc::kNotReady:
      return "not ready";
    case Errc::kTimeout:
      return "timeout";
    case Errc::kUnavailable:
      return "unavailable";
    case Errc::kPermissionDenied:
      return "permission denied";
    case Errc::kIoError:
      return "i/o error";
    case Errc::kCorrupt:
      return "corrupt";
  }
  return "unknown";
}

}  // namespace colag
