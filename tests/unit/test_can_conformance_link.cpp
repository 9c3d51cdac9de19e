// The CanBus conformance suite on the in-memory link the simulator uses.
#include "can_bus_conformance.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "colag/hal/sim/can_link.hpp"

namespace colag::test {
namespace {

struct SimPair final : CanBusPair {
  hal::scripted::ManualClock clock_;
  hal::sim::SimCanLink link{clock_};
  hal::CanBus& a() override { return link.board(); }
  hal::CanBus& b() override { return link.motor(); }
  const hal::Clock& clock() const override { return clock_; }
  void wait(Duration d) override { clock_.advance(d); }
};

INSTANTIATE_TEST_SUITE_P(SimCanLink, CanBusConformance,
                         ::testing::Values(CanBusImplementation{
                             "SimCanLink",
                             [](std::string&) -> std::unique_ptr<CanBusPair> {
                               return std::make_unique<SimPair>();
                             }}),
                         [](const auto& p) { return p.param.name; });

}  // namespace
}  // namespace colag::test
