#pragma once
// What a UGV board keeps across a restart of its program: its last pose estimate, written once
// a second (a temporary file renamed over the old one: a crash mid-write leaves the previous
// one whole). A ugv_fw started again within `max_age_s` claims that pose, with its start-guess
// sigma, instead of the configured start guess, which is true only at the mission's start: the
// UAV comes to where it really stands, and the other UGVs keep clear of where it really stands,
// until a relative pose initialises its estimator again. Its body stood still meanwhile (the
// motor controller stops without commands: 200 ms).
#include <optional>
#include <string>

#include "colag/common/geometry.hpp"

namespace colag::ugv {

struct ResumeState {
  Pose2 pose;
  double age_s = 0.0;  // how old the file is (wall clock)
};

// False with `error` when the file cannot be written.
bool save_resume_state(const std::string& path, const Pose2& pose, std::string& error);

// The saved pose if the file exists, parses, and is at most `max_age_s` old; otherwise empty,
// with `why` saying why (empty when there is no file: a first start).
std::optional<ResumeState> load_resume_state(const std::string& path, double max_age_s,
                                             std::string& why);

}  // namespace colag::ugv
