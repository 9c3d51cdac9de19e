#include "colag/hal/linux/camera_model.hpp"

#include <fstream>

#include <opencv2/core.hpp>

namespace colag::linux_hal {

bool CameraIntrinsics::distorted() const {
  for (double k : distortion) {
    if (k != 0.0) return true;
  }
  return false;
}

bool load_intrinsics(const std::string& path, CameraIntrinsics& out, std::string& error) {
  // cv::FileStorage reports malformed files by throwing; this runs at start-up, never in a task.
  // OpenCV would also log its own error for a missing file: say it once, ourselves.
  if (!std::ifstream(path).good()) {
    error = path + ": cannot open the calibration file";
    return false;
  }
  try {
    cv::FileStorage fs(path, cv::FileStorage::READ);
    if (!fs.isOpened()) {
      error = path + ": cannot open the calibration file";
      return false;
    }
    CameraIntrinsics c;
    cv::Mat k, d;
    fs["camera_matrix"] >> k;
    fs["distortion_coefficients"] >> d;
    if (k.rows != 3 || k.cols != 3) {
      error = path + ": camera_matrix: missing or not 3x3";
      return false;
    }
    k.convertTo(k, CV_64F);
    c.fx = k.at<double>(0, 0);
    c.fy = k.at<double>(1, 1);
    c.cx = k.at<double>(0, 2);
    c.cy = k.at<double>(1, 2);
    if (!(c.fx > 0.0) || !(c.fy > 0.0)) {
      error = path + ": camera_matrix: focal lengths must be positive";
      return false;
    }
    if (!d.empty()) {
      if (d.total() < 4) {
        error = path + ": distortion_coefficients: expected at least 4 values";
        return false;
      }
      d = d.reshape(1, 1);
      d.convertTo(d, CV_64F);
      for (std::size_t i = 0; i < c.distortion.size() && i < d.total(); ++i)
        c.distortion[i] = d.at<double>(0, static_cast<int>(i));
    }
    const cv::FileNode w = fs["image_width"], h = fs["image_height"];
    if (w.empty() || h.empty() || static_cast<int>(w) <= 0 || static_cast<int>(h) <= 0) {
      error = path + ": image_width/image_height: missing or not positive";
      return false;
    }
    c.width = static_cast<int>(w);
    c.height = static_cast<int>(h);
    out = c;
    return true;
  } catch (const cv::Exception& e) {
    error = path + ": not a valid OpenCV calibration file (" + e.msg + ")";
    return false;
  }
}

Pose3 downward_camera_mount(const Vec3& offset_in_body) {
  Mat3 r;  // columns: the optical axes in body coordinates
  r.col(0) = -Vec3::UnitY();
  r.col(1) = -Vec3::UnitX();
  r.col(2) = -Vec3::UnitZ();
  return {offset_in_body, Quat(r)};
}

}  // namespace colag::linux_hal
