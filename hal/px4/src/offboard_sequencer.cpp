#include "colag/hal/px4/offboard_sequencer.hpp"

namespace colag::hal::px4 {

namespace {

bool in_offboard(const Px4Status& s) {
  return s.nav_state == kNavStateOffboard;
}

}  // namespace

void OffboardSequencer::on_status(TimePoint now, const Px4Status& s) {
  heard(now);
  last_status_ = now;
  status_ = s;
  if (s.armed) ever_armed_ = true;
}

void OffboardSequencer::on_ack(TimePoint now, std::uint32_t command, std::uint8_t result) {
  heard(now);
  const bool awaiting = state_ == State::kModeRequested || state_ == State::kArmRequested ||
                        state_ == State::kLanding;
  if (!awaiting || acked_ || command != pending_.command) return;
  if (result == kAckAccepted) {
    acked_ = true;
  } else if (result == kAckInProgress || result == kAckTemporarilyRejected) {
    sent_at_ = now;  // asked again after ack_timeout (a temporary refusal counts an attempt)
  } else if (state_ == State::kLanding) {
    fault_ = msg::FlightFault::kRefused;  // it lands or not on its own now: nothing else to do
    acked_ = true;
  } else {
    lose(msg::FlightFault::kRefused);
  }
}

void OffboardSequencer::land(TimePoint now) {
  if (state_ == State::kLost || state_ == State::kLanding || state_ == State::kLanded) return;
  if (!ever_armed_) {  // never flew: nothing to land
    state_ = State::kLanded;
    entered_ = now;
    return;
  }
  request(now, State::kLanding, {kCmdNavLand, 0.0F, 0.0F});
}

void OffboardSequencer::lose(msg::FlightFault why) {
  state_ = State::kLost;
  fault_ = why;
  send_now_ = false;
}

void OffboardSequencer::request(TimePoint now, State next, const Px4Command& c) {
  state_ = next;
  entered_ = now;
  pending_ = c;
  attempts_ = 1;
  acked_ = false;
  sent_at_ = now;
  send_now_ = true;
}

bool OffboardSequencer::retry_due(TimePoint now) const {
  return !acked_ && now - sent_at_ >= config_.ack_timeout;
}

bool OffboardSequencer::step(TimePoint now, Px4Command& command) {
  if (started_ == kNever) started_ = entered_ = now;
  const bool engaging = state_ == State::kPriming || state_ == State::kModeRequested ||
                        state_ == State::kArmRequested || state_ == State::kTakingOff ||
                        state_ == State::kInControl;
  // Silence: nothing at all (the agent, the link or PX4 is gone), or no status (the one message
  // that says it is still ours).
  if (engaging && (now - last_heard_ > config_.silence_timeout ||
                   now - last_status_ > config_.status_timeout)) {
    lose(msg::FlightFault::kSilent);
  }
  // A failsafe at any point of the take-off or the flight ends it.
  if (engaging && state_ != State::kLost && status_.failsafe) lose(msg::FlightFault::kFailsafe);

  switch (state_) {
    case State::kWaitingForPx4:
      fault_ = wrong_release_ ? msg::FlightFault::kWrongRelease
               : (last_heard_ == kNever && now - started_ > config_.status_timeout)
                   ? msg::FlightFault::kSilent
                   : msg::FlightFault::kNone;
      if (last_status_ != kNever && now - last_status_ <= config_.status_timeout &&
          last_setpoint_ != kNever && now - last_setpoint_ <= config_.setpoint_timeout) {
        fault_ = msg::FlightFault::kNone;
        state_ = State::kPriming;
        entered_ = now;
      }
      break;
    case State::kPriming:
      if (now - entered_ >= config_.prime_time)
        request(now, State::kModeRequested, {kCmdDoSetMode, kModeCustom, kMainModeOffboard});
      break;
    case State::kModeRequested:
      if (acked_ || in_offboard(status_)) {
        if (status_.armed) {
          state_ = State::kTakingOff;
          entered_ = now;
        } else {
          request(now, State::kArmRequested, {kCmdArmDisarm, 1.0F, 0.0F});
        }
      }
      break;
    case State::kArmRequested:
      if (acked_ || status_.armed) {
        state_ = State::kTakingOff;
        entered_ = now;
      }
      break;
    case State::kTakingOff:
      if (status_.armed && in_offboard(status_)) {
        state_ = State::kInControl;
        entered_ = now;
      } else if (now - entered_ > config_.confirm_timeout) {
        lose(msg::FlightFault::kRefused);  // accepted, yet never armed in offboard
      }
      break;
    case State::kInControl:
      if (!status_.armed) {
        lose(msg::FlightFault::kDisarmed);
      } else if (!in_offboard(status_)) {
        lose(msg::FlightFault::kLeftOffboard);
      }
      break;
    case State::kLanding:
      if (ever_armed_ && !status_.armed && last_status_ > entered_) {
        state_ = State::kLanded;
        entered_ = now;
      }
      break;
    case State::kLanded:
    case State::kLost:
      break;
  }

  // An unacknowledged command is sent again, up to its attempts.
  const bool awaiting = state_ == State::kModeRequested || state_ == State::kArmRequested ||
                        state_ == State::kLanding;
  if (awaiting && !send_now_ && retry_due(now)) {
    if (attempts_ >= config_.command_attempts) {
      if (state_ == State::kLanding) {
        fault_ = msg::FlightFault::kNoAck;
        acked_ = true;  // stop asking; it is reported
      } else {
        lose(msg::FlightFault::kNoAck);
      }
    } else {
      ++attempts_;
      sent_at_ = now;
      send_now_ = true;
    }
  }
  if (!send_now_) return false;
  send_now_ = false;
  command = pending_;
  return true;
}

bool OffboardSequencer::streaming(TimePoint now) const {
  const bool engaging = state_ == State::kPriming || state_ == State::kModeRequested ||
                        state_ == State::kArmRequested || state_ == State::kTakingOff ||
                        state_ == State::kInControl;
  return engaging && last_setpoint_ != kNever && now - last_setpoint_ <= config_.setpoint_timeout;
}

FlightStatus OffboardSequencer::status() const {
  switch (state_) {
    case State::kInControl:
      return {msg::UavFlight::kInControl, msg::FlightFault::kNone};
    case State::kLanding:
    case State::kLanded:
      return {msg::UavFlight::kLanding, fault_};
    case State::kLost:
      return {msg::UavFlight::kLost, fault_};
    default:
      return {msg::UavFlight::kStarting, fault_};
  }
}

}  // namespace colag::hal::px4
