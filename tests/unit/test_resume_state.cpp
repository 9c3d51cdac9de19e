// The pose a UGV board keeps across a restart of its program (resume_state.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "colag/ugv/app/resume_state.hpp"

namespace colag::ugv {
namespace {

class ResumeStateTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("colag_resume_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / "ugv1.state").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
  std::string path_;
};

TEST_F(ResumeStateTest, KeepsThePoseAcrossARestart) {
  std::string why, error;
  EXPECT_FALSE(load_resume_state(path_, 300.0, why));  // a first start: nothing kept
  EXPECT_TRUE(why.empty());
  ASSERT_TRUE(save_resume_state(path_, {Vec2(-2.11, 4.84), -1.56}, error)) << error;
  ASSERT_TRUE(save_resume_state(path_, {Vec2(-2.2, 4.5), -1.5}, error)) << error;  // replaced
  const auto kept = load_resume_state(path_, 300.0, why);
  ASSERT_TRUE(kept) << why;
  EXPECT_NEAR(kept->pose.p.x(), -2.2, 1e-6);
  EXPECT_NEAR(kept->pose.p.y(), 4.5, 1e-6);
  EXPECT_NEAR(kept->pose.yaw_rad, -1.5, 1e-6);
  EXPECT_LT(kept->age_s, 5.0);
  EXPECT_FALSE(std::filesystem::exists(path_ + ".tmp"));
}

TEST_F(ResumeStateTest, AnOldOrForeignFileIsNotBelieved) {
  std::string why, error;
  ASSERT_TRUE(save_resume_state(path_, {Vec2(1, 2), 0.3}, error));
  std::filesystem::last_write_time(
      path_, std::filesystem::file_time_type::clock::now() - std::chrono::minutes(10));
  EXPECT_FALSE(load_resume_state(path_, 300.0, why));  // the robot may have been carried away
  EXPECT_NE(why.find("old"), std::string::npos) << why;
  std::ofstream(path_) << "x: 1\ny: 2\n";
  EXPECT_FALSE(load_resume_state(path_, 300.0, why));
  EXPECT_NE(why.find("not a UGV state file"), std::string::npos) << why;
  std::ofstream(path_) << "colag-ugv-state 1 nan 2 0\n";
  EXPECT_FALSE(load_resume_state(path_, 300.0, why));
  EXPECT_FALSE(load_resume_state(dir_.string(), 300.0, why));
  EXPECT_NE(why.find("not a file"), std::string::npos) << why;
  EXPECT_FALSE(save_resume_state((dir_ / "no" / "such" / "dir").string(), {}, error));
  EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace colag::ugv
