// The camera RPE on real AprilTag detections in synthesised images (tag_scene.hpp).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "colag/hal/linux/tag_pose_estimator.hpp"
#include "tag_scene.hpp"

namespace colag::linux_hal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TagPoseConfig config_for(const CameraIntrinsics& camera) {
  TagPoseConfig c;
  c.camera = camera;
  c.camera_in_uav = Pose3{};  // UAV frame = optical frame unless a test says otherwise
  c.tag_size_m = 0.2;
  (void)c.tags.push_back({7, 3, Pose3{}});
  (void)c.tags.push_back({11, 5, Pose3{}});
  return c;
}

struct Case {
  double distance_m, tilt_deg, yaw_deg, dx_m;
  double max_position_error_m, max_angle_error_deg;
};

// Accuracy over distance and viewing angle, 640 x 480, blur and noise, decimation 2. The bounds
// are the measured errors (printed) with margin; depth is what degrades with distance. Heading
// is the rotation about the tag's normal (a UGV's yaw when the tag lies flat on it).
TEST(TagPoseEstimator, RecoversTheTagPoseAcrossDistancesAndTilts) {
  const CameraIntrinsics camera;  // 640 x 480, f = 500 px (65 deg horizontal field of view)
  TagPoseEstimator rpe(config_for(camera));
  const std::array<Case, 8> cases{{{1.0, 0, 0, 0.0, 0.005, 0.5},
                                   {1.0, 40, 30, 0.3, 0.005, 0.5},
                                   {2.0, 0, 90, 0.0, 0.01, 0.5},
                                   {2.0, 30, -20, -0.5, 0.01, 0.5},
                                   {3.0, 0, 10, 0.4, 0.03, 1.0},
                                   {3.0, 45, 0, 0.0, 0.06, 1.0},
                                   {4.0, 20, 45, -0.6, 0.05, 1.5},
                                   {4.5, 0, 0, 0.0, 0.08, 1.5}}};
  std::uint64_t seed = 1;
  for (const Case& k : cases) {
    const test::TagInScene tag{
        7, test::tag_ahead(k.distance_m, k.tilt_deg * kDeg, k.yaw_deg * kDeg, k.dx_m, 0.1), 0.2};
    const cv::Mat frame = test::render_tags(camera, {&tag, 1}, {.seed = seed++});
    std::array<hal::RelativePoseDetection, 4> out;
    ASSERT_EQ(rpe.detect(frame, TimePoint{std::chrono::seconds(2)}, out), 1u)
        << "no detection at " << k.distance_m << " m, tilt " << k.tilt_deg;
    EXPECT_EQ(out[0].ugv_id, 3);
    EXPECT_EQ(out[0].stamp, TimePoint{std::chrono::seconds(2)});
    const double dp = (out[0].ugv_in_uav.p - tag.tag_in_camera.p).norm();
    const double da = test::heading_error(out[0].ugv_in_uav.q, tag.tag_in_camera.q) / kDeg;
    const double tilt = test::angle_between(out[0].ugv_in_uav.q, tag.tag_in_camera.q) / kDeg;
    std::printf(
        "  d %.1f m tilt %2.0f deg: position %.4f m, heading %.2f deg (full rotation %.2f)\n",
        k.distance_m, k.tilt_deg, dp, da, tilt);
    EXPECT_LT(dp, k.max_position_error_m) << "at " << k.distance_m << " m, tilt " << k.tilt_deg;
    EXPECT_LT(da, k.max_angle_error_deg) << "at " << k.distance_m << " m, tilt " << k.tilt_deg;
    // A small square seen head-on from afar leaves its tilt ambiguous (the planar-pose
    // ambiguity); the UGVs' EKF uses position and heading only.
    EXPECT_LT(tilt, 20.0);
    // The stated uncertainty covers the error (3 sigma).
    EXPECT_LT(dp, 3.0 * std::sqrt(out[0].covariance(0, 0)));
  }
}

TEST(TagPoseEstimator, SeveralTagsInOneFrameAndUnknownIdsIgnored) {
  const CameraIntrinsics camera;
  TagPoseEstimator rpe(config_for(camera));
  const std::array<test::TagInScene, 3> tags{{{7, test::tag_ahead(2.0, 0, 0, -0.8, 0), 0.2},
                                              {11, test::tag_ahead(2.5, 0.3, 1.0, 0.8, 0), 0.2},
                                              {23, test::tag_ahead(2.0, 0, 0, 0.0, 0.5), 0.2}}};
  const cv::Mat frame = test::render_tags(camera, tags);
  std::array<hal::RelativePoseDetection, 4> out;
  ASSERT_EQ(rpe.detect(frame, TimePoint{}, out), 2u);
  EXPECT_EQ(rpe.counters().unknown_tags, 1u);  // tag 23 is nobody's
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& expected = out[i].ugv_id == 3 ? tags[0] : tags[1];
    EXPECT_TRUE(out[i].ugv_id == 3 || out[i].ugv_id == 5);
    EXPECT_LT((out[i].ugv_in_uav.p - expected.tag_in_camera.p).norm(), 0.04);
  }
  EXPECT_NE(out[0].ugv_id, out[1].ugv_id);
}

TEST(TagPoseEstimator, CameraMountAndTagPlacementAreApplied) {
  const CameraIntrinsics camera;
  TagPoseConfig config = config_for(camera);
  config.camera_in_uav = downward_camera_mount(Vec3(0.1, 0.0, -0.05));
  config.tags[0].tag_in_body = Pose3{Vec3(0.0, 0.0, 0.3),  // on top of the UGV, facing up
                                     Quat(Eigen::AngleAxisd(std::numbers::pi, Vec3::UnitX()))};
  TagPoseEstimator rpe(config);
  // A UGV 1.5 m below the UAV, 0.4 m ahead and 0.2 m to the left, turned by 30 degrees.
  const Pose3 ugv_in_uav{Vec3(0.4, 0.2, -1.5), quat_from_yaw(30 * kDeg)};
  const Pose3 tag_in_camera =
      config.camera_in_uav.inverse().compose(ugv_in_uav).compose(config.tags[0].tag_in_body);
  const test::TagInScene tag{7, tag_in_camera, 0.2};
  std::array<hal::RelativePoseDetection, 2> out;
  ASSERT_EQ(rpe.detect(test::render_tags(camera, {&tag, 1}), TimePoint{}, out), 1u);
  EXPECT_LT((out[0].ugv_in_uav.p - ugv_in_uav.p).norm(), 0.02);
  EXPECT_NEAR(wrap_angle(yaw_of(out[0].ugv_in_uav.q) - 30 * kDeg), 0.0, 1.5 * kDeg);
}

TEST(TagPoseEstimator, DistortedLensIsUndistortedFirst) {
  CameraIntrinsics camera;
  camera.distortion = {-0.25, 0.08, 0.0, 0.0, 0.0};  // a typical wide-angle barrel
  TagPoseEstimator rpe(config_for(camera));
  CameraIntrinsics pinhole = camera;
  pinhole.distortion = {};
  TagPoseEstimator naive(config_for(pinhole));  // ignores the distortion
  const test::TagInScene tag{7, test::tag_ahead(2.0, 0.2, 0.3, 0.9, 0.6), 0.2};
  const cv::Mat frame = test::render_tags(camera, {&tag, 1});
  std::array<hal::RelativePoseDetection, 2> out, wrong;
  ASSERT_EQ(rpe.detect(frame, TimePoint{}, out), 1u);
  ASSERT_EQ(naive.detect(frame, TimePoint{}, wrong), 1u);
  const double err = (out[0].ugv_in_uav.p - tag.tag_in_camera.p).norm();
  const double naive_err = (wrong[0].ugv_in_uav.p - tag.tag_in_camera.p).norm();
  std::printf("  distorted lens: error %.4f m undistorted, %.4f m if ignored\n", err, naive_err);
  EXPECT_LT(err, 0.03);
  EXPECT_GT(naive_err, 2.0 * err);
}

TEST(TagPoseEstimator, BadFramesGiveNoDetectionAndNoCrash) {
  const CameraIntrinsics camera;
  TagPoseEstimator rpe(config_for(camera));
  std::array<hal::RelativePoseDetection, 2> out;
  EXPECT_EQ(rpe.detect(cv::Mat(), TimePoint{}, out), 0u);                           // empty
  EXPECT_EQ(rpe.detect(cv::Mat::zeros(480, 640, CV_8UC1), TimePoint{}, out), 0u);   // black
  EXPECT_EQ(rpe.detect(cv::Mat::zeros(240, 320, CV_8UC1), TimePoint{}, out), 0u);   // wrong size
  EXPECT_EQ(rpe.detect(cv::Mat::zeros(480, 640, CV_32FC1), TimePoint{}, out), 0u);  // wrong type
  cv::Mat garbage(480, 640, CV_8UC1);
  cv::RNG(5).fill(garbage, cv::RNG::UNIFORM, 0, 256);  // corrupt: pure noise
  EXPECT_EQ(rpe.detect(garbage, TimePoint{}, out), 0u);
  // A valid frame with the tag's lower half overwritten (a torn buffer).
  const test::TagInScene tag{7, test::tag_ahead(1.5), 0.2};
  cv::Mat torn = test::render_tags(camera, {&tag, 1});
  torn.rowRange(240, 480).setTo(cv::Scalar(0));
  EXPECT_EQ(rpe.detect(torn, TimePoint{}, out), 0u);
  EXPECT_EQ(rpe.counters().bad_frames, 3u);
  // Output full: nothing written past it.
  EXPECT_EQ(rpe.detect(test::render_tags(camera, {&tag, 1}), TimePoint{}, {}), 0u);
}

TEST(TagPoseEstimator, ColourFramesAreConverted) {
  const CameraIntrinsics camera;
  TagPoseEstimator rpe(config_for(camera));
  const test::TagInScene tag{11, test::tag_ahead(1.5, 0.2), 0.2};
  cv::Mat bgr;
  cv::cvtColor(test::render_tags(camera, {&tag, 1}), bgr, cv::COLOR_GRAY2BGR);
  std::array<hal::RelativePoseDetection, 2> out;
  ASSERT_EQ(rpe.detect(bgr, TimePoint{}, out), 1u);
  EXPECT_EQ(out[0].ugv_id, 5);
}

TEST(TagPoseEstimator, UncertaintyGrowsWithDistanceAndObliqueness) {
  TagPoseEstimator rpe(config_for(CameraIntrinsics{}));
  const double near = rpe.covariance(test::tag_ahead(1.0))(0, 0);
  const double far = rpe.covariance(test::tag_ahead(3.0))(0, 0);
  const double oblique = rpe.covariance(test::tag_ahead(1.0, 60 * kDeg))(0, 0);
  EXPECT_GT(far, 4.0 * near);
  EXPECT_GT(oblique, 2.0 * near);
  EXPECT_GT(rpe.covariance(test::tag_ahead(3.0))(3, 3), rpe.covariance(test::tag_ahead(1.0))(3, 3));
}

}  // namespace
}  // namespace colag::linux_hal
