// The board programs' YAML configuration: arbitrary documents through the UGV and UAV config
// readers. Invariants: no exception escapes; a rejected document names the problem; an accepted
// one holds values inside the documented ranges.
#include <string>

#include "colag/uav/app/uav_config.hpp"
#include "colag/ugv/app/ugv_config.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  std::string error;
  if (data[0] & 1) {
    colag::ugv::UgvBoardConfig c;
    if (colag::ugv::parse_ugv_config(text, "fuzz.yaml", c, error)) {
      COLAG_FUZZ_CHECK(error.empty());
      COLAG_FUZZ_CHECK(c.nav.id < colag::limits::kMaxUgvs);
      COLAG_FUZZ_CHECK(c.wheels.wheel_radius_m > 0.0 && c.wheels.track_width_m > 0.0);
      COLAG_FUZZ_CHECK(c.nav.schedule.control.period.count() > 0 &&
                       c.nav.schedule.planning.period.count() > 0 &&
                       c.nav.schedule.control.budget.count() > 0);
      COLAG_FUZZ_CHECK(c.common.dds_domain <= 232);
    } else {
      COLAG_FUZZ_CHECK(error.rfind("fuzz.yaml: ", 0) == 0);
    }
  } else {
    // The calibration file it names is read relative to the (nonexistent) directory "fuzz/";
    // naming a device or kernel file (an endless /dev/zero) is an operator's mistake, not
    // input to fuzz.
    for (const char* special : {"dev/", "proc/", "sys/"})
      if (text.find(special) != std::string::npos) return 0;
    colag::uav::UavBoardConfig c;
    if (colag::uav::parse_uav_config(text, "fuzz/uav.yaml", c, error)) {
      COLAG_FUZZ_CHECK(error.empty());
      COLAG_FUZZ_CHECK(c.common.dds_domain <= 232);
    } else {
      COLAG_FUZZ_CHECK(error.rfind("fuzz/uav.yaml: ", 0) == 0);
    }
  }
  return 0;
}
