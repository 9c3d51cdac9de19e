#pragma once
// hal::CanBus on Linux SocketCAN (PF_CAN / CAN_RAW): a non-blocking raw socket bound to one
// interface (can0 on a board, vcan0 in the HIL VM), with
// - kernel receive filters for the ids we use (nothing else wakes us up),
// - error frames enabled: bus-off and error-passive are surfaced in stats(), counted, and never
//   returned as data,
// - kernel receive time stamps (SO_TIMESTAMPNS, converted to the given monotonic clock),
// - the kernel's count of frames dropped for a full socket queue (SO_RXQ_OVFL),
// - send with a deadline (waits for queue space with poll(), never past the deadline),
// - reconnect: when the interface goes down or disappears the socket is closed and reopened
//   every `reconnect_period` from within send()/receive(), so `ip link set can0 down/up` or a
//   USB adapter re-plugged heals by itself.
#include <cstdint>
#include <string>

#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/hal/can_bus.hpp"
#include "colag/hal/clock.hpp"

namespace colag::linux_hal {

struct CanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0x7FF;  // standard id, exact match
  bool extended = false;
};

struct SocketCanConfig {
  std::string interface = "can0";
  StaticVector<CanFilter, limits::kCanFilters> filters;  // empty: receive every data frame
  Duration reconnect_period = std::chrono::milliseconds(500);
};

struct SocketCanStats {
  std::uint64_t reconnects = 0;  // successful reopens after the interface went away
  int last_errno = 0;
};

class SocketCanBus final : public hal::CanBus {
 public:
  SocketCanBus(const SocketCanConfig& config, const hal::Clock& clock);
  ~SocketCanBus() override;
  SocketCanBus(const SocketCanBus&) = delete;
  SocketCanBus& operator=(const SocketCanBus&) = delete;

  // Opens and binds the socket: kUnavailable (no AF_CAN in this kernel, no such interface) or
  // kIoError, with errno in driver_stats().last_errno.
  Status open();
  bool is_open() const { return fd_ >= 0; }

  Status send(const hal::CanFrame& frame, TimePoint deadline) override;
  bool receive(hal::CanFrame& out) override;
  hal::CanBusStats stats() const override { return stats_; }
  const SocketCanStats& driver_stats() const { return driver_; }

 private:
  void close_socket();
  bool ensure_open();  // reopens after reconnect_period; false while down
  void lost(int err);  // the interface went down or away
  void on_error_frame(const std::uint8_t* data, std::uint32_t id);

  SocketCanConfig config_;
  const hal::Clock& clock_;
  int fd_ = -1;
  bool was_open_ = false;
  TimePoint next_reopen_{};
  hal::CanBusStats stats_;
  SocketCanStats driver_;
  std::uint32_t kernel_drops_ = 0;  // SO_RXQ_OVFL's running count
};

}  // namespace colag::linux_hal
