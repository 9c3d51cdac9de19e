#include "colag/hal/can/can_base.hpp"

namespace colag::hal::can {

IdFilters base_filters(const BaseConfig& config) {
  IdFilters f;
  switch (config.protocol) {
    case BaseProtocol::kColag: {
      const WheelProtocolConfig& p = config.colag;
      const std::uint32_t mask = p.extended_ids ? 0x1FFFFFFFu : 0x7FFu;
      (void)f.push_back({p.counts_id, mask, p.extended_ids});
      (void)f.push_back({p.speeds_id, mask, p.extended_ids});
      break;
    }
    case BaseProtocol::kOdrive:
      // Every frame of each axis's node: its heartbeat and encoder estimates among them.
      (void)f.push_back({static_cast<std::uint32_t>(config.odrive.left.node) << 5, 0x7E0u, false});
      (void)f.push_back({static_cast<std::uint32_t>(config.odrive.right.node) << 5, 0x7E0u, false});
      break;
    case BaseProtocol::kAgilexV2:
      (void)f.push_back({agilex::kSystemStateId, 0x7FFu, false});
      (void)f.push_back({agilex::kOdometryId, 0x7FFu, false});
      break;
  }
  return f;
}

IdFilters command_filters(const BaseConfig& config) {
  IdFilters f;
  switch (config.protocol) {
    case BaseProtocol::kColag: {
      const WheelProtocolConfig& p = config.colag;
      (void)f.push_back({p.command_id, p.extended_ids ? 0x1FFFFFFFu : 0x7FFu, p.extended_ids});
      break;
    }
    case BaseProtocol::kOdrive:
      return base_filters(config);  // a node's commands share its id range with its feedback
    case BaseProtocol::kAgilexV2:
      (void)f.push_back({agilex::kMotionCommandId, 0x7FFu, false});
      (void)f.push_back({agilex::kControlModeId, 0x7FFu, false});
      (void)f.push_back({agilex::kStateResetId, 0x7FFu, false});
      break;
  }
  return f;
}

CanBase::CanBase(CanBus& bus, const BaseConfig& config, const WheelGeometry& wheels) {
  switch (config.protocol) {
    case BaseProtocol::kColag:
      odometry_ = &colag_odometry_.emplace(bus, config.colag, wheels);
      drive_ = &colag_drive_.emplace(bus, config.colag, wheels);
      break;
    case BaseProtocol::kOdrive:
      odometry_ = &odrive_.emplace(bus, config.odrive, wheels);
      drive_ = &*odrive_;
      break;
    case BaseProtocol::kAgilexV2:
      odometry_ = &agilex_.emplace(bus, config.agilex, wheels);
      drive_ = &*agilex_;
      break;
  }
}

BaseCounters CanBase::counters() const {
  BaseCounters c;
  if (colag_odometry_) {
    const CanOdometryCounters& o = colag_odometry_->counters();
    c = {o.frames, o.samples, o.unknown_id + o.wrong_dlc + o.bad_checksum, o.lost_frames,
         o.implausible};
  } else if (odrive_) {
    const OdriveCounters& o = odrive_->counters();
    c = {o.frames, o.samples, o.bad_frames, 0, o.implausible, o.watchdog_clears};
  } else if (agilex_) {
    const AgilexCounters& o = agilex_->counters();
    c = {o.frames, o.samples, o.bad_frames, o.lost_states, o.implausible};
  }
  return c;
}

}  // namespace colag::hal::can
