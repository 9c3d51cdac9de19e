#pragma once
// The camera RPE device (hal::RelativePoseSensor on a real camera): a capture thread reads
// frames with OpenCV (a V4L2 device, a video file or an image sequence), runs the
// TagPoseEstimator on each and publishes the newest detections; the UAV task's poll() only
// copies them under a short lock (no allocation, no waiting on the camera).
#include <array>
#include <atomic>
#include <mutex>
#include <string>
#include <thread>

#include "colag/common/status.hpp"
#include "colag/hal/clock.hpp"
#include "colag/hal/linux/tag_pose_estimator.hpp"

namespace colag::linux_hal {

struct CameraSource {
  // "/dev/video0" or "0" (a V4L2 device), a video file, or an image sequence ("f_%03d.png").
  std::string uri = "/dev/video0";
  Duration latency = std::chrono::milliseconds(30);  // exposure to the frame being read
  Duration min_period{};  // paces files and sequences (0: as fast as they decode)
  bool loop = false;      // files and sequences: start over at the end
};

struct CameraStats {
  std::uint64_t frames = 0;
  std::uint64_t read_failures = 0;  // no frame (device gone, end of file)
  std::uint64_t reopens = 0;
  std::uint64_t longest_frame_us = 0;  // detection time of the slowest frame
};

class CameraRpe final : public hal::RelativePoseSensor {
 public:
  CameraRpe(const TagPoseConfig& config, const CameraSource& source, const hal::Clock& clock);
  ~CameraRpe() override;
  CameraRpe(const CameraRpe&) = delete;
  CameraRpe& operator=(const CameraRpe&) = delete;

  // Opens the source and starts the capture thread; kUnavailable if it cannot be opened.
  Status start();
  void stop();

  std::size_t poll(std::span<hal::RelativePoseDetection> out) override;
  CameraStats stats() const;
  TagPoseCounters detector_counters() const;

 private:
  void run();

  TagPoseEstimator estimator_;
  CameraSource source_;
  const hal::Clock& clock_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  struct Impl;
  std::unique_ptr<Impl> impl_;  // the cv::VideoCapture

  mutable std::mutex mutex_;  // guards everything below
  std::array<hal::RelativePoseDetection, limits::kMaxRpeDetectionsPerFrame> latest_{};
  std::size_t latest_count_ = 0;
  std::uint64_t latest_seq_ = 0, read_seq_ = 0;
  CameraStats stats_;
  TagPoseCounters counters_;
};

}  // namespace colag::linux_hal
