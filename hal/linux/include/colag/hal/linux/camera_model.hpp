#pragma once
// A calibrated pinhole camera: OpenCV's intrinsics (camera matrix, distortion coefficients,
// pixel-centre convention) as written by OpenCV's calibration tools, and where the camera sits
// on the UAV.
#include <array>
#include <string>

#include "colag/common/geometry.hpp"

namespace colag::linux_hal {

struct CameraIntrinsics {
  int width = 640, height = 480;
  double fx = 500.0, fy = 500.0, cx = 319.5, cy = 239.5;
  std::array<double, 5> distortion{};  // k1 k2 p1 p2 k3 (OpenCV order); zeros: none
  bool distorted() const;
};

// Reads an OpenCV calibration file (YAML or XML, cv::FileStorage): `camera_matrix` (3x3),
// `distortion_coefficients` (4, 5 or more values; the first 5 are used), `image_width`,
// `image_height`. False with `error` naming the key and the problem.
bool load_intrinsics(const std::string& path, CameraIntrinsics& out, std::string& error);

// A camera looking straight down from the UAV body, image top towards the UAV's nose:
// optical z = body -z, optical x = body -y, optical y = body -x.
Pose3 downward_camera_mount(const Vec3& offset_in_body = Vec3::Zero());

}  // namespace colag::linux_hal
