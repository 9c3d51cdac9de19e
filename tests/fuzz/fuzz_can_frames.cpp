// CAN traffic as the UGV's base drivers receive it: a sequence of frames (any id, dlc, data,
// time step) through the three protocols' decoders (ours, ODrive CAN Simple, AgileX V2), then
// through one protocol's driver (CanBase: odometry polled, drive commanded between bursts).
// Invariants: a frame that decodes re-encodes to the same bytes; every frame is counted; every
// odometry sample is finite, physically plausible and in time order; the ODrive decoder accepts
// only its node's standard-id feedback of the right length; a driver never crashes on any
// traffic and always answers with a health.
#include <cmath>
#include <cstring>

#include "colag/hal/can/agilex_protocol.hpp"
#include "colag/hal/can/can_base.hpp"
#include "colag/hal/can/can_wheel_odometry.hpp"
#include "colag/hal/can/odrive_protocol.hpp"
#include "colag/hal/can/wheel_protocol.hpp"
#include "fuzz_input.hpp"

namespace {

using namespace colag;
using namespace colag::hal;
using colag::fuzz::FuzzInput;

// A bus that replays the frames decoded from the input.
class ReplayBus final : public CanBus {
 public:
  explicit ReplayBus(FuzzInput& in) : in_(in) {}

  Status send(const CanFrame&, TimePoint) override { return Status::ok(); }
  bool receive(CanFrame& out) override {
    if (++calls_ % 5 == 0) return false;  // frames arrive in bursts of four between polls
    // 13 bytes per frame: time step us u16, id u16 (top bits: extended, fix checksum), dlc u8,
    // data 8.
    if (in_.remaining() < 13) return false;
    now_ += std::chrono::microseconds(in_.u16());
    const std::uint16_t id = in_.u16();
    out = CanFrame{};
    out.stamp = now_;
    out.extended = (id & 0x8000) != 0;
    out.id = id & 0x3FFF;  // may exceed 11 bits: an invalid frame the decoder must refuse
    out.dlc = static_cast<std::uint8_t>(in_.u8() % 16);
    for (auto& b : out.data)
      b = in_.u8();
    // Let the fuzzer reach past the checksum: on request, make it right.
    if (id & 0x4000) out.data[7] = can::crc8(out.data, 7);
    ++delivered_;
    return true;
  }
  CanBusStats stats() const override { return {}; }
  std::uint64_t delivered() const { return delivered_; }

 private:
  FuzzInput& in_;
  TimePoint now_{};
  std::uint64_t delivered_ = 0;
  std::uint64_t calls_ = 0;
};

void check_roundtrip(const CanFrame& f, const can::WheelProtocolConfig& cfg) {
  can::DecodedFrame d;
  if (can::decode(f, cfg, d) != can::DecodeError::kNone) return;
  CanFrame again;
  switch (d.kind) {
    case can::FrameKind::kCounts:
      again = can::encode(d.counts, cfg);
      break;
    case can::FrameKind::kSpeeds:
      again = can::encode(d.speeds, cfg);
      break;
    case can::FrameKind::kCommand:
      again = can::encode(d.command, cfg);
      break;
  }
  COLAG_FUZZ_CHECK(again.id == f.id && again.dlc == f.dlc && is_valid(again));
  // Reserved bits are not round-tripped (the decoder ignores them), the rest is.
  COLAG_FUZZ_CHECK(can::decode(again, cfg, d) == can::DecodeError::kNone);
}

void check_odrive(const CanFrame& f, std::uint8_t node) {
  namespace od = can::odrive;
  od::Feedback fb;
  if (od::decode(f, node, fb) != od::DecodeError::kNone) return;
  COLAG_FUZZ_CHECK(!f.extended && (f.id >> 5) == node);
  COLAG_FUZZ_CHECK(fb.command == od::Command::kHeartbeat
                       ? f.dlc >= 7
                       : fb.command == od::Command::kEncoderEstimates && f.dlc == 8);
}

void check_agilex(const CanFrame& f) {
  namespace ag = can::agilex;
  ag::Decoded d;
  if (ag::decode(f, d) != ag::DecodeError::kNone) return;
  COLAG_FUZZ_CHECK(!f.extended && d.id == f.id);
  CanFrame again;
  switch (d.id) {
    case ag::kMotionCommandId:
      again = ag::encode(d.motion);
      break;
    case ag::kMotionStateId:
      again = ag::encode_motion_state(d.motion);
      break;
    case ag::kOdometryId:
      again = ag::encode(d.odometry);
      break;
    default:
      return;  // system state and the commands have reserved bytes: not round-tripped
  }
  // Motion frames: lateral speed and steering (bytes 4..7) are not used by a differential base.
  const std::size_t used = d.id == ag::kOdometryId ? 8 : 4;
  COLAG_FUZZ_CHECK(again.id == f.id && again.dlc == 8 &&
                   std::memcmp(again.data, f.data, used) == 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput in(data, size);
  can::WheelProtocolConfig cfg;
  cfg.counts_id = 0x101 + (in.u8() & 3);  // a few id layouts
  can::WheelGeometry geometry;

  // Pass 1: every frame through the pure codecs (ours, and ODrive's for one node).
  {
    FuzzInput copy(in.rest(), in.remaining());
    ReplayBus bus(copy);
    CanFrame f;
    const auto node = static_cast<std::uint8_t>(cfg.counts_id & 3);
    while (copy.remaining() >= 13) {
      if (!bus.receive(f)) continue;
      check_roundtrip(f, cfg);
      check_odrive(f, node);
      check_agilex(f);
    }
  }

  // Pass 2: the whole sequence through one protocol's driver, polled every few frames.
  can::BaseConfig base;
  base.colag = cfg;
  base.protocol = static_cast<can::BaseProtocol>(cfg.counts_id % 3);
  base.odrive.left.node = static_cast<std::uint8_t>(cfg.counts_id & 3);
  base.odrive.right.node = static_cast<std::uint8_t>(base.odrive.left.node + 1);
  ReplayBus bus(in);
  can::CanBase driver(bus, base, geometry);
  WheelOdometrySample s;
  TimePoint last{};
  // The fastest a wheel can really turn, with margin for time-stamp jitter.
  const double max_plausible = 4.0 * geometry.max_wheel_speed_mps;
  for (;;) {
    if (!driver.odometry().poll(s)) {
      if (in.remaining() < 13) break;
      (void)driver.drive().command({last + std::chrono::milliseconds(20), 0.3, 0.1});
      const DriveHealth h = driver.drive().health();
      COLAG_FUZZ_CHECK(h.fault <= msg::BaseFault::kLowBattery);
      continue;
    }
    COLAG_FUZZ_CHECK(std::isfinite(s.v_mps) && std::isfinite(s.omega_radps));
    COLAG_FUZZ_CHECK(std::abs(s.v_mps) <= max_plausible);
    COLAG_FUZZ_CHECK(std::abs(s.omega_radps) <= 2.0 * max_plausible / geometry.track_width_m);
    COLAG_FUZZ_CHECK(s.stamp > last);
    last = s.stamp;
  }
  const can::BaseCounters c = driver.counters();
  COLAG_FUZZ_CHECK(c.frames == bus.delivered());
  COLAG_FUZZ_CHECK(c.samples <= c.frames);
  return 0;
}
