#include "colag/hal/linux/tag_pose_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/apriltag_pose.h>
#include <apriltag/tag36h11.h>
}

namespace colag::linux_hal {

struct TagPoseEstimator::Impl {
  apriltag_family_t* family = tag36h11_create();
  apriltag_detector_t* detector = apriltag_detector_create();
  cv::Mat undistort_x, undistort_y;  // remap tables, when the lens is distorted
  cv::Mat grey, undistorted;         // reused frame buffers
  ~Impl() {
    apriltag_detector_destroy(detector);
    tag36h11_destroy(family);
  }
};

TagPoseEstimator::TagPoseEstimator(const TagPoseConfig& config)
    : config_(config), impl_(std::make_unique<Impl>()) {
  apriltag_detector_add_family_bits(impl_->detector, impl_->family,
                                    std::clamp(config.max_hamming, 0, 2));
  impl_->detector->quad_decimate = std::max(1.0f, config.decimate);
  impl_->detector->quad_sigma = config.blur_sigma;
  impl_->detector->nthreads = std::max(1, config.threads);
  impl_->detector->refine_edges = true;
  const CameraIntrinsics& c = config.camera;
  if (c.distorted()) {
    // Undistort the whole frame once per frame with precomputed tables: the detector and the
    // pose estimator then work with the ideal pinhole model of the same camera matrix.
    const cv::Matx33d k(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
    cv::initUndistortRectifyMap(k, cv::Mat(c.distortion), cv::noArray(), k,
                                cv::Size(c.width, c.height), CV_16SC2, impl_->undistort_x,
                                impl_->undistort_y);
  }
}

TagPoseEstimator::~TagPoseEstimator() = default;

Eigen::Matrix4d TagPoseEstimator::covariance(const Pose3& tag_in_camera) const {
  const RpeNoiseModel& m = config_.noise;
  const double d = tag_in_camera.p.norm();
  const Vec3 normal = tag_in_camera.q * Vec3::UnitZ();
  const double cos_view = d > 0.0 ? std::abs(normal.dot(tag_in_camera.p / d)) : 1.0;
  const double scale = 1.0 / std::max(cos_view, m.min_cos);
  const double sp = (m.position_base_m + m.position_per_m2 * d * d) * scale;
  const double sy = (m.yaw_base_rad + m.yaw_per_m2 * d * d) * scale;
  Eigen::Matrix4d cov = Eigen::Matrix4d::Zero();
  cov.diagonal() << sp * sp, sp * sp, sp * sp, sy * sy;  // isotropic: the same in any frame
  return cov;
}

std::size_t TagPoseEstimator::detect(const cv::Mat& image, TimePoint stamp,
                                     std::span<hal::RelativePoseDetection> out) {
  ++counters_.frames;
  const CameraIntrinsics& cam = config_.camera;
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3) ||
      image.cols != cam.width || image.rows != cam.height || image.dims != 2) {
    ++counters_.bad_frames;  // also a frame of another size: the intrinsics would not apply
    return 0;
  }
  const cv::Mat* grey = &image;
  if (image.channels() == 3) {
    cv::cvtColor(image, impl_->grey, cv::COLOR_BGR2GRAY);
    grey = &impl_->grey;
  }
  if (!impl_->undistort_x.empty()) {
    cv::remap(*grey, impl_->undistorted, impl_->undistort_x, impl_->undistort_y, cv::INTER_LINEAR);
    grey = &impl_->undistorted;
  }
  image_u8_t im{grey->cols, grey->rows, static_cast<std::int32_t>(grey->step[0]), grey->data};
  zarray_t* found = apriltag_detector_detect(impl_->detector, &im);
  std::size_t n = 0;
  for (int i = 0; i < zarray_size(found); ++i) {
    apriltag_detection_t* det = nullptr;
    zarray_get(found, i, &det);
    if (det->decision_margin < config_.min_decision_margin) {
      ++counters_.weak_tags;
      continue;
    }
    const auto tag = std::find_if(config_.tags.begin(), config_.tags.end(),
                                  [&](const TagAssignment& t) { return t.tag_id == det->id; });
    if (tag == config_.tags.end()) {
      ++counters_.unknown_tags;
      continue;
    }
    // apriltag's corners sit +0.5 px from OpenCV's pixel-centre convention: shift the centre.
    apriltag_detection_info_t info{det,    config_.tag_size_m, cam.fx,
                                   cam.fy, cam.cx + 0.5,       cam.cy + 0.5};
    apriltag_pose_t pose{};
    (void)estimate_tag_pose(&info, &pose);
    Mat3 r;
    Vec3 t;
    for (int row = 0; row < 3; ++row) {
      t[row] = pose.t->data[row];
      for (int col = 0; col < 3; ++col)
        r(row, col) = pose.R->data[row * 3 + col];
    }
    std::free(pose.R);  // Debian's libapriltag does not export matd_destroy
    std::free(pose.t);
    if (!all_finite(t) || !r.allFinite()) {
      ++counters_.rejected_pose;
      continue;
    }
    if (t.norm() > config_.max_range_m) {
      ++counters_.out_of_range;
      continue;
    }
    const Pose3 tag_in_camera{t, Quat(r).normalized()};
    hal::RelativePoseDetection d;
    d.stamp = stamp;
    d.ugv_id = tag->ugv_id;
    d.ugv_in_uav = config_.camera_in_uav.compose(tag_in_camera).compose(tag->tag_in_body.inverse());
    d.covariance = covariance(tag_in_camera);
    // Several tags on one UGV: keep the most certain view.
    auto same = std::find_if(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n),
                             [&](const auto& o) { return o.ugv_id == d.ugv_id; });
    if (same != out.begin() + static_cast<std::ptrdiff_t>(n)) {
      if (d.covariance(0, 0) < same->covariance(0, 0)) *same = d;
      continue;
    }
    if (n < out.size()) {
      out[n++] = d;
      ++counters_.detections;
    }
  }
  apriltag_detections_destroy(found);
  return n;
}

}  // namespace colag::linux_hal
