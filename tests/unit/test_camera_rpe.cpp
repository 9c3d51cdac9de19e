// The camera RPE device on an image sequence (OpenCV's capture, the capture thread, poll), and
// the calibration-file loader.
#include <gtest/gtest.h>

#include <unistd.h>
#include <array>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "colag/hal/linux/camera_rpe.hpp"
#include "tag_scene.hpp"

namespace colag::linux_hal {
namespace {

class FixedClock final : public hal::Clock {
 public:
  TimePoint now() const override { return TimePoint{std::chrono::seconds(10)}; }
};

std::filesystem::path temp_dir(const std::string& name) {
  auto dir =
      std::filesystem::temp_directory_path() / ("colag_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(CameraRpe, ReadsAnImageSequenceAndPublishesTheNewestDetections) {
  const auto dir = temp_dir("camera_seq");
  CameraIntrinsics camera;
  for (int i = 0; i < 3; ++i) {  // the tag moves 0.1 m per frame
    const test::TagInScene tag{7, test::tag_ahead(1.5, 0.1, 0.2, 0.1 * i, 0.0), 0.2};
    char name[32];
    std::snprintf(name, sizeof name, "frame_%02d.png", i);
    ASSERT_TRUE(cv::imwrite((dir / name).string(), test::render_tags(camera, {&tag, 1})));
  }
  TagPoseConfig config;
  config.camera = camera;
  config.camera_in_uav = Pose3{};
  config.tag_size_m = 0.2;
  (void)config.tags.push_back({7, 4, Pose3{}});
  FixedClock clock;
  CameraRpe rpe(config, {(dir / "frame_%02d.png").string(), std::chrono::milliseconds(30)}, clock);
  ASSERT_TRUE(rpe.start().is_ok());
  // The sequence ends after three frames; the thread stops by itself.
  for (int i = 0; i < 200 && rpe.stats().read_failures == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  rpe.stop();
  EXPECT_EQ(rpe.stats().frames, 3u);
  EXPECT_EQ(rpe.detector_counters().detections, 3u);
  std::array<hal::RelativePoseDetection, 4> out;
  ASSERT_EQ(rpe.poll(out), 1u);  // only the newest frame
  EXPECT_EQ(out[0].ugv_id, 4);
  EXPECT_EQ(out[0].stamp, TimePoint{std::chrono::milliseconds(9970)});  // clock - latency
  EXPECT_NEAR(out[0].ugv_in_uav.p.x(), 0.2, 0.01);
  EXPECT_EQ(rpe.poll(out), 0u);  // read already
  std::filesystem::remove_all(dir);
}

TEST(CameraRpe, MissingSourceIsReportedNotFatal) {
  FixedClock clock;
  CameraRpe rpe(TagPoseConfig{}, {"/nonexistent/frame_%02d.png"}, clock);
  const Status s = rpe.start();
  EXPECT_EQ(s.code(), Errc::kUnavailable);
  std::array<hal::RelativePoseDetection, 2> out;
  EXPECT_EQ(rpe.poll(out), 0u);
}

TEST(CameraIntrinsicsFile, LoadsOpenCvCalibrationYaml) {
  const auto dir = temp_dir("calib");
  const auto path = (dir / "camera.yaml").string();
  {
    cv::FileStorage fs(path, cv::FileStorage::WRITE);
    fs << "image_width" << 1280 << "image_height" << 720;
    fs << "camera_matrix" << cv::Mat(cv::Matx33d(910.5, 0, 640.2, 0, 909.8, 359.7, 0, 0, 1));
    fs << "distortion_coefficients" << cv::Mat(cv::Matx<double, 1, 5>(-0.1, 0.02, 0.001, 0, 0));
  }
  CameraIntrinsics c;
  std::string error;
  ASSERT_TRUE(load_intrinsics(path, c, error)) << error;
  EXPECT_EQ(c.width, 1280);
  EXPECT_EQ(c.height, 720);
  EXPECT_DOUBLE_EQ(c.fx, 910.5);
  EXPECT_DOUBLE_EQ(c.cy, 359.7);
  EXPECT_DOUBLE_EQ(c.distortion[0], -0.1);
  EXPECT_TRUE(c.distorted());
  std::filesystem::remove_all(dir);
}

TEST(CameraIntrinsicsFile, ErrorsNameTheKey) {
  const auto dir = temp_dir("calib_bad");
  const auto write = [&](const std::string& text) {
    auto path = (dir / "bad.yaml").string();
    std::ofstream(path) << text;
    return path;
  };
  CameraIntrinsics c;
  std::string error;
  EXPECT_FALSE(load_intrinsics((dir / "missing.yaml").string(), c, error));
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
  EXPECT_FALSE(load_intrinsics(write("%YAML:1.0\nimage_width: 640\n"), c, error));
  EXPECT_NE(error.find("camera_matrix"), std::string::npos) << error;
  EXPECT_FALSE(load_intrinsics(write("%YAML:1.0\ncamera_matrix: [1, 2\n  garbage: {"), c, error));
  EXPECT_FALSE(error.empty());
  EXPECT_FALSE(load_intrinsics(
      write("%YAML:1.0\ncamera_matrix: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n"
            "  data: [500, 0, 320, 0, 500, 240, 0, 0, 1]\nimage_height: 480\n"),
      c, error));
  EXPECT_NE(error.find("image_width"), std::string::npos) << error;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace colag::linux_hal
