// The mission figure: a map of any size or shape fits the picture, the caption below it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "colag/sim/mission_png.hpp"

namespace colag {
namespace {

// Columns (of the map area, above the caption) where an obstacle's dark grey is drawn.
std::vector<int> dark_columns(const cv::Mat& img, int rows) {
  std::vector<int> cols;
  for (int x = 0; x < img.cols; ++x) {
    for (int y = 0; y < rows; ++y) {
      if (img.at<cv::Vec3b>(y, x) == cv::Vec3b(70, 70, 70)) {
        cols.push_back(x);
        break;
      }
    }
  }
  return cols;
}

TEST(MissionPicture, AWideMapIsNotCroppedAndTheCaptionStaysBelowIt) {
  mission::MissionTrace trace;
  trace.world.min_x_m = -30.0;
  trace.world.max_x_m = 30.0;
  trace.world.min_y_m = -4.0;
  trace.world.max_y_m = 4.0;
  // Obstacles at both ends of a 60 x 8 m arena (a square 36 m view cut both off).
  trace.world.boxes.push_back({Vec2(-28.0, 0.0), Vec2(0.5, 0.5), 1.0});
  trace.world.boxes.push_back({Vec2(28.0, 0.0), Vec2(0.5, 0.5), 1.0});
  mission::MissionOutcome outcome;
  outcome.reach_time_s = -1.0;
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("colag_png_" + std::to_string(::getpid()) + ".png"))
                               .string();
  std::string error;
  ASSERT_TRUE(programs::draw_mission(trace, outcome, path, error)) << error;
  const cv::Mat img = cv::imread(path);
  std::filesystem::remove(path);
  ASSERT_FALSE(img.empty());
  // 800 px for 62 m: the map is ~110 px tall, then the axes and the caption.
  EXPECT_LT(img.rows, 500) << "a wide map drawn as a square";
  const std::vector<int> dark = dark_columns(img, img.rows - 200);
  ASSERT_FALSE(dark.empty()) << "no obstacle drawn above the caption";
  EXPECT_LT(dark.front(), img.cols / 4) << "the west obstacle is missing";
  EXPECT_GT(dark.back(), 3 * img.cols / 4) << "the east obstacle is missing";
}

}  // namespace
}  // namespace colag
