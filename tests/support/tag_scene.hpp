#pragma once
// Synthesised camera images of AprilTags (tag36h11) at known poses, for testing the camera RPE
// on real detections: each tag is rendered by apriltag itself, warped into a pinhole camera's
// image (OpenCV pixel-centre convention), then the frame is blurred, noised and optionally
// distorted with the camera's lens model.
#include <cstdint>
#include <span>

#include <opencv2/core.hpp>

#include "colag/hal/linux/camera_model.hpp"

namespace colag::test {

struct TagInScene {
  int id = 0;
  Pose3 tag_in_camera;  // apriltag's tag frame (x right, y down, z into the tag)
  double size_m = 0.2;  // black square edge
};

struct SceneStyle {
  double blur_sigma_px = 0.8;
  double noise_sigma = 4.0;  // grey levels
  int background = 150;
  std::uint64_t seed = 1;
};

// The 8-bit grey frame; tags behind the camera are skipped.
cv::Mat render_tags(const linux_hal::CameraIntrinsics& camera, std::span<const TagInScene> tags,
                    const SceneStyle& style = {});

// A pose looking at a tag `distance_m` ahead, tilted by `tilt_rad` about the tag's x axis and
// turned by `yaw_rad` about its normal, shifted sideways by (dx, dy) in the image plane.
Pose3 tag_ahead(double distance_m, double tilt_rad = 0.0, double yaw_rad = 0.0, double dx = 0.0,
                double dy = 0.0);

// The angle of the rotation between two orientations.
double angle_between(const Quat& a, const Quat& b);
// The error of `estimate` about `truth`'s z axis (the tag's normal): the angle between their x
// axes projected on the plane normal to it.
double heading_error(const Quat& estimate, const Quat& truth);

}  // namespace colag::test
