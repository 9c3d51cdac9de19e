#include "tag_scene.hpp"

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/common/image_u8.h>
#include <apriltag/tag36h11.h>
}

namespace colag::test {

namespace {
constexpr int kPxPerCell = 16;  // the rendered tag's resolution before warping

cv::Mat tag_texture(apriltag_family_t* family, int id) {
  image_u8_t* img = apriltag_to_image(family, id);  // 10 x 10 cells incl. the white border
  cv::Mat cells(img->height, img->width, CV_8UC1, img->buf, static_cast<std::size_t>(img->stride));
  cv::Mat big;
  cv::resize(cells, big, cv::Size(), kPxPerCell, kPxPerCell, cv::INTER_NEAREST);
  image_u8_destroy(img);
  return big;
}

// Distorts an ideal pinhole image with the camera's lens model.
cv::Mat distort(const cv::Mat& ideal, const linux_hal::CameraIntrinsics& c) {
  const cv::Matx33d k(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  std::vector<cv::Point2f> pixels;
  pixels.reserve(static_cast<std::size_t>(ideal.total()));
  for (int v = 0; v < ideal.rows; ++v)
    for (int u = 0; u < ideal.cols; ++u)
      pixels.emplace_back(static_cast<float>(u), static_cast<float>(v));
  std::vector<cv::Point2f> undistorted;
  cv::undistortPoints(pixels, undistorted, k, cv::Mat(c.distortion), cv::noArray(), k);
  cv::Mat map(ideal.rows, ideal.cols, CV_32FC2, undistorted.data());
  cv::Mat out;
  cv::remap(ideal, out, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  return out;
}
}  // namespace

cv::Mat render_tags(const linux_hal::CameraIntrinsics& c, std::span<const TagInScene> tags,
                    const SceneStyle& style) {
  cv::Mat frame(c.height, c.width, CV_8UC1, cv::Scalar(style.background));
  apriltag_family_t* family = tag36h11_create();
  for (const TagInScene& tag : tags) {
    const cv::Mat texture = tag_texture(family, tag.id);
    const double cell = tag.size_m / 8.0;
    const auto n = static_cast<float>(texture.cols - 1);
    const cv::Point2f src[4] = {{0, 0}, {n, 0}, {n, n}, {0, n}};
    cv::Point2f dst[4];
    bool visible = true;
    for (int i = 0; i < 4; ++i) {
      // Pixel centre u of the texture lies at ((u + 0.5) / k - 5) cells from the tag centre.
      const Vec3 on_tag(((src[i].x + 0.5) / kPxPerCell - 5.0) * cell,
                        ((src[i].y + 0.5) / kPxPerCell - 5.0) * cell, 0.0);
      const Vec3 p = tag.tag_in_camera.transform(on_tag);
      if (p.z() <= 0.05) visible = false;
      dst[i] = {static_cast<float>(c.fx * p.x() / p.z() + c.cx),
                static_cast<float>(c.fy * p.y() / p.z() + c.cy)};
    }
    if (!visible) continue;
    cv::warpPerspective(texture, frame, cv::getPerspectiveTransform(src, dst), frame.size(),
                        cv::INTER_LINEAR, cv::BORDER_TRANSPARENT);
  }
  tag36h11_destroy(family);
  if (style.blur_sigma_px > 0.0) cv::GaussianBlur(frame, frame, cv::Size(), style.blur_sigma_px);
  if (c.distorted()) frame = distort(frame, c);
  if (style.noise_sigma > 0.0) {
    cv::Mat noise(frame.size(), CV_16SC1);
    cv::RNG rng(style.seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, style.noise_sigma);
    cv::Mat sum;
    frame.convertTo(sum, CV_16SC1);
    sum += noise;
    sum.convertTo(frame, CV_8UC1);  // saturating
  }
  return frame;
}

Pose3 tag_ahead(double distance_m, double tilt_rad, double yaw_rad, double dx, double dy) {
  const Quat q = Quat(Eigen::AngleAxisd(tilt_rad, Vec3::UnitX())) *
                 Quat(Eigen::AngleAxisd(yaw_rad, Vec3::UnitZ()));
  return {Vec3(dx, dy, distance_m), q};
}

double angle_between(const Quat& a, const Quat& b) {
  return a.angularDistance(b);
}

double heading_error(const Quat& estimate, const Quat& truth) {
  const Vec3 n = truth * Vec3::UnitZ();
  const Vec3 x = truth * Vec3::UnitX();
  Vec3 e = estimate * Vec3::UnitX();
  e -= e.dot(n) * n;
  return std::abs(std::atan2(x.cross(e).dot(n), x.dot(e)));
}

}  // namespace colag::test
