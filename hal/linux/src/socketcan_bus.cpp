#include "colag/hal/linux/socketcan_bus.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>

namespace colag::linux_hal {

namespace {
// Kernel stamps are CLOCK_REALTIME; our clock is monotonic: shift by the current offset.
TimePoint to_monotonic(const timespec& stamp, TimePoint mono_now) {
  timespec real_now{};
  clock_gettime(CLOCK_REALTIME, &real_now);
  const std::int64_t age_ns = (std::int64_t{real_now.tv_sec} - stamp.tv_sec) * 1'000'000'000 +
                              (real_now.tv_nsec - stamp.tv_nsec);
  return mono_now - std::chrono::nanoseconds(std::max<std::int64_t>(0, age_ns));
}
}  // namespace

SocketCanBus::SocketCanBus(const SocketCanConfig& config, const hal::Clock& clock)
    : config_(config), clock_(clock) {}

SocketCanBus::~SocketCanBus() {
  close_socket();
}

void SocketCanBus::close_socket() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

Status SocketCanBus::open() {
  close_socket();
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    driver_.last_errno = errno;
    return {Errc::kUnavailable, "socketcan: no PF_CAN sockets (can/can-raw modules loaded?)"};
  }
  ifreq ifr{};
  if (config_.interface.size() >= sizeof ifr.ifr_name) {
    ::close(fd);
    return {Errc::kInvalidArgument, "socketcan: interface name too long"};
  }
  std::memcpy(ifr.ifr_name, config_.interface.c_str(), config_.interface.size() + 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) < 0) {
    driver_.last_errno = errno;
    ::close(fd);
    return {Errc::kUnavailable, "socketcan: no such CAN interface"};
  }
  // Receive filters: only our ids reach the socket queue.
  can_filter filters[limits::kCanFilters];
  for (std::size_t i = 0; i < config_.filters.size(); ++i) {
    const CanFilter& f = config_.filters[i];
    filters[i].can_id = f.extended ? (f.id | CAN_EFF_FLAG) : f.id;
    filters[i].can_mask = (f.mask & (f.extended ? CAN_EFF_MASK : CAN_SFF_MASK)) | CAN_EFF_FLAG |
                          CAN_RTR_FLAG;  // data frames of the right id kind only
  }
  const can_err_mask_t errors = CAN_ERR_TX_TIMEOUT | CAN_ERR_CRTL | CAN_ERR_BUSOFF |
                                CAN_ERR_BUSERROR | CAN_ERR_RESTARTED | CAN_ERR_PROT;
  const int one = 1;
  const bool ok =
      (config_.filters.empty() ||
       ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters,
                    static_cast<socklen_t>(sizeof(can_filter) * config_.filters.size())) == 0) &&
      ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors, sizeof errors) == 0 &&
      ::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &one, sizeof one) == 0 &&
      ::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one) == 0;
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (!ok || ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) {
    driver_.last_errno = errno;
    ::close(fd);
    return {Errc::kIoError, "socketcan: socket options or bind failed"};
  }
  fd_ = fd;
  if (was_open_) ++driver_.reconnects;
  was_open_ = true;
  return Status::ok();
}

void SocketCanBus::lost(int err) {
  driver_.last_errno = err;
  close_socket();
  next_reopen_ = clock_.now() + config_.reconnect_period;
}

bool SocketCanBus::ensure_open() {
  if (fd_ >= 0) return true;
  if (!was_open_ || clock_.now() < next_reopen_) return false;
  if (!open()) {
    next_reopen_ = clock_.now() + config_.reconnect_period;
    return false;
  }
  return true;
}

Status SocketCanBus::send(const hal::CanFrame& frame, TimePoint deadline) {
  if (!hal::is_valid(frame)) {
    ++stats_.tx_failures;
    return {Errc::kInvalidArgument, "socketcan: bad frame (dlc > 8 or id too large)"};
  }
  if (!ensure_open()) {
    ++stats_.tx_failures;
    return {Errc::kUnavailable, "socketcan: interface down"};
  }
  can_frame raw{};
  raw.can_id = frame.extended ? (frame.id | CAN_EFF_FLAG) : frame.id;
  raw.len = frame.dlc;
  std::memcpy(raw.data, frame.data, frame.dlc);
  for (;;) {
    if (::write(fd_, &raw, sizeof raw) == static_cast<ssize_t>(sizeof raw)) {
      ++stats_.tx_frames;
      return Status::ok();
    }
    const int err = errno;
    if (err == ENETDOWN || err == ENODEV || err == ENXIO) {
      lost(err);
      ++stats_.tx_failures;
      return {Errc::kUnavailable, "socketcan: interface down"};
    }
    if (err != EAGAIN && err != ENOBUFS && err != EINTR) {
      driver_.last_errno = err;
      ++stats_.tx_failures;
      return {Errc::kIoError, "socketcan: write failed"};
    }
    // The transmit queue is full: wait for room, but not past the deadline.
    const Duration left = deadline - clock_.now();
    if (left <= Duration::zero()) {
      ++stats_.tx_failures;
      return {Errc::kTimeout, "socketcan: transmit queue full until the deadline"};
    }
    pollfd p{fd_, POLLOUT, 0};
    const auto ms = std::chrono::ceil<std::chrono::milliseconds>(left).count();
    (void)::poll(&p, 1, static_cast<int>(std::min<std::int64_t>(ms, 1000)));
    // ENOBUFS does not wake poll() on some drivers: the loop re-checks the deadline anyway.
  }
}

void SocketCanBus::on_error_frame(const std::uint8_t* data, std::uint32_t id) {
  ++stats_.error_frames;
  if (id & CAN_ERR_BUSOFF) stats_.bus_off = true;
  if (id & CAN_ERR_RESTARTED) stats_.bus_off = false;
  if (id & CAN_ERR_CRTL) {
    const std::uint8_t ctrl = data[1];
    if (ctrl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) stats_.error_passive = true;
    if (ctrl & CAN_ERR_CRTL_ACTIVE) stats_.error_passive = false;
  }
}

bool SocketCanBus::receive(hal::CanFrame& out) {
  if (!ensure_open()) return false;
  for (;;) {
    can_frame raw{};
    iovec iov{&raw, sizeof raw};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(std::uint32_t))];
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
    if (n < 0) {
      const int err = errno;
      if (err == ENETDOWN || err == ENODEV || err == ENXIO)
        lost(err);
      else if (err != EAGAIN && err != EINTR)
        driver_.last_errno = err;
      return false;
    }
    if (n != static_cast<ssize_t>(sizeof raw)) continue;  // CAN FD or truncated: not ours
    TimePoint stamp = clock_.now();
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level != SOL_SOCKET) continue;
      if (c->cmsg_type == SO_TIMESTAMPNS) {
        timespec ts{};
        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
        stamp = to_monotonic(ts, stamp);
      } else if (c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t drops = 0;
        std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
        stats_.rx_overruns += drops - kernel_drops_;  // the kernel's count only grows
        kernel_drops_ = drops;
      }
    }
    if (raw.can_id & CAN_ERR_FLAG) {
      on_error_frame(raw.data, raw.can_id & CAN_ERR_MASK);
      continue;
    }
    if (raw.can_id & CAN_RTR_FLAG) continue;
    out.stamp = stamp;
    out.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
    out.id = raw.can_id & (out.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    out.dlc = std::min<std::uint8_t>(raw.len, 8);
    std::memcpy(out.data, raw.data, out.dlc);
    std::fill(out.data + out.dlc, out.data + 8, 0);
    ++stats_.rx_frames;
    return true;
  }
}

}  // namespace colag::linux_hal
