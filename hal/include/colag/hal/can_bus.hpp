#pragma once
#include <cstdint>

#include "colag/common/status.hpp"
#include "colag/common/time.hpp"

namespace colag::hal {

struct CanFrame {
  TimePoint stamp;       // receive time (kernel time stamp on SocketCAN); unused on send
  std::uint32_t id = 0;  // 11-bit, or 29-bit when `extended`
  bool extended = false;
  std::uint8_t dlc = 0;  // 0..8 data bytes (classic CAN)
  std::uint8_t data[8] = {};
};

struct CanBusStats {
  std::uint64_t rx_frames = 0;
  std::uint64_t tx_frames = 0;
  std::uint64_t tx_failures = 0;   // deadline missed or driver error
  std::uint64_t rx_overruns = 0;   // frames dropped because the receive queue was full
  std::uint64_t error_frames = 0;  // bus errors reported by the controller
  bool bus_off = false;
  bool error_passive = false;
};

// A classic-CAN frame any bus can carry: at most 8 data bytes, an 11-bit id (29-bit when
// extended). Every CanBus refuses other frames with kInvalidArgument.
constexpr bool is_valid(const CanFrame& f) {
  return f.dlc <= 8 && f.id <= (f.extended ? 0x1FFFFFFFu : 0x7FFu);
}

// A raw classic-CAN bus. Non-blocking: receive returns false when nothing is queued.
class CanBus {
 public:
  virtual ~CanBus() = default;
  // Sends one frame; gives up (kTimeout) when it cannot be queued before `deadline`.
  virtual Status send(const CanFrame& frame, TimePoint deadline) = 0;
  virtual bool receive(CanFrame& out) = 0;
  virtual CanBusStats stats() const = 0;
};

}  // namespace colag::hal
