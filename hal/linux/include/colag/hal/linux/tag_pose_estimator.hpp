#pragma once
// Camera relative-pose estimation (the UAV's RPE device): grey image -> AprilTag detector
// (tag36h11) -> tag pose from the four corners (apriltag's estimate_tag_pose, with the camera's
// intrinsics) -> the pose of each UGV in the UAV body frame, with a covariance that grows with
// distance and viewing angle.
//
// Frames: the optical frame is OpenCV's (x right, y down, z forward); the tag frame is
// apriltag's (x right, y down, z into the tag); `camera_in_uav` places the optical frame in
// the UAV body, each tag's `tag_in_body` places the tag on its UGV.
//
// Owns the detector (allocated in the constructor); `detect` itself allocates inside the
// apriltag library, so it runs in the camera's own thread (CameraRpe), never in a task step.
#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include "colag/common/limits.hpp"
#include "colag/common/static_vector.hpp"
#include "colag/hal/linux/camera_model.hpp"
#include "colag/hal/relative_pose_sensor.hpp"

namespace cv {
class Mat;
}

namespace colag::linux_hal {

struct TagAssignment {
  int tag_id = 0;
  RobotId ugv_id = 0;
  Pose3 tag_in_body;  // where the tag sits on the UGV
};

// One standard deviation of the pose, as a function of distance d and viewing angle a (between
// the optical ray to the tag and the tag's normal): sigma = base + per_m2 * d^2, divided by
// max(cos a, min_cos). Depth from a small square is what degrades first, quadratically with d.
struct RpeNoiseModel {
  double position_base_m = 0.01;
  double position_per_m2 = 0.01;
  double yaw_base_rad = 0.01;
  double yaw_per_m2 = 0.005;
  double min_cos = 0.3;
};

struct TagPoseConfig {
  CameraIntrinsics camera;
  Pose3 camera_in_uav = downward_camera_mount();
  double tag_size_m = 0.16;  // edge of the black square (8 of tag36h11's 10 cells)
  StaticVector<TagAssignment, limits::kMaxRpeTags> tags;
  float decimate = 2.0f;  // apriltag quad_decimate
  int threads = 1;        // apriltag worker threads
  float blur_sigma = 0.0f;
  double min_decision_margin = 30.0;  // weaker decodes are ignored
  int max_hamming = 1;                // bit errors corrected (tag36h11 allows up to 2)
  double max_range_m = 5.0;           // the paper's RPE range
  RpeNoiseModel noise;
};

struct TagPoseCounters {
  std::uint64_t frames = 0;
  std::uint64_t bad_frames = 0;     // empty, wrong type or too small
  std::uint64_t detections = 0;     // tags reported as UGV poses
  std::uint64_t unknown_tags = 0;   // decoded ids no UGV is assigned
  std::uint64_t weak_tags = 0;      // below the decision margin
  std::uint64_t out_of_range = 0;   // farther than max_range_m
  std::uint64_t rejected_pose = 0;  // non-finite pose
};

class TagPoseEstimator {
 public:
  explicit TagPoseEstimator(const TagPoseConfig& config);
  ~TagPoseEstimator();
  TagPoseEstimator(const TagPoseEstimator&) = delete;
  TagPoseEstimator& operator=(const TagPoseEstimator&) = delete;

  // Detects the UGVs in one frame (8-bit grey, or BGR which is converted) taken at `stamp`.
  // Writes at most out.size() detections and returns how many; a bad frame gives 0.
  std::size_t detect(const cv::Mat& image, TimePoint stamp,
                     std::span<hal::RelativePoseDetection> out);

  const TagPoseCounters& counters() const { return counters_; }
  const TagPoseConfig& config() const { return config_; }
  // The pose covariance (x, y, z, yaw in the UAV frame) for a tag at `tag_in_camera`.
  Eigen::Matrix4d covariance(const Pose3& tag_in_camera) const;

 private:
  struct Impl;
  TagPoseConfig config_;
  TagPoseCounters counters_;
  std::unique_ptr<Impl> impl_;  // the apriltag detector and family, undistortion maps
};

}  // namespace colag::linux_hal
