#pragma once
// The contract every hal::CanBus implementation keeps, as one GoogleTest suite run against the
// in-memory SimCanLink (host, every build) and SocketCAN on vcan0 (inside the HIL VM): each
// implementation provides a factory of two connected endpoints.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <ostream>
#include <string>

#include "colag/hal/can_bus.hpp"
#include "colag/hal/clock.hpp"

namespace colag::test {

struct CanBusPair {
  virtual ~CanBusPair() = default;
  virtual hal::CanBus& a() = 0;
  virtual hal::CanBus& b() = 0;
  virtual const hal::Clock& clock() const = 0;
  // Lets time pass (a real sleep on SocketCAN, a clock step in simulation).
  virtual void wait(Duration d) = 0;
};

struct CanBusImplementation {
  std::string name;
  // Returns nullptr and sets `why` when the implementation cannot run here (e.g. no AF_CAN).
  std::function<std::unique_ptr<CanBusPair>(std::string& why)> make;
};

// Receives on `bus`, polling every millisecond for up to `ms` of the pair's time (frames on a real
// bus arrive asynchronously).
bool receive_within(CanBusPair& pair, hal::CanBus& bus, hal::CanFrame& out, int ms = 1000);

inline void PrintTo(const CanBusImplementation& i, std::ostream* os) {
  *os << i.name;
}

class CanBusConformance : public ::testing::TestWithParam<CanBusImplementation> {
 protected:
  void SetUp() override {
    std::string why;
    pair_ = GetParam().make(why);
    if (!pair_) GTEST_SKIP() << GetParam().name << " not available here: " << why;
  }
  bool receive_within(hal::CanBus& bus, hal::CanFrame& out) {
    return test::receive_within(*pair_, bus, out);
  }
  std::unique_ptr<CanBusPair> pair_;
};

}  // namespace colag::test
