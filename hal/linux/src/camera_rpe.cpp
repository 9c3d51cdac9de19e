#include "colag/hal/linux/camera_rpe.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <opencv2/videoio.hpp>

namespace colag::linux_hal {

struct CameraRpe::Impl {
  cv::VideoCapture capture;
  bool is_device = false;
};

namespace {
bool is_index(const std::string& uri) {
  return !uri.empty() && std::all_of(uri.begin(), uri.end(), [](char ch) {
    return std::isdigit(static_cast<unsigned char>(ch)) != 0;
  });
}

bool open(cv::VideoCapture& capture, const std::string& uri) {
  // A bare number or /dev/ node is a V4L2 device, a printf pattern an image sequence; anything
  // else a video file for whichever backend OpenCV has.
  try {
    if (is_index(uri)) return capture.open(std::stoi(uri), cv::CAP_V4L2);
    if (uri.rfind("/dev/", 0) == 0) return capture.open(uri, cv::CAP_V4L2);
    if (uri.find('%') != std::string::npos) return capture.open(uri, cv::CAP_IMAGES);
    return capture.open(uri);
  } catch (const cv::Exception&) {
    return false;
  }
}
}  // namespace

CameraRpe::CameraRpe(const TagPoseConfig& config, const CameraSource& source,
                     const hal::Clock& clock)
    : estimator_(config), source_(source), clock_(clock), impl_(std::make_unique<Impl>()) {
  impl_->is_device = source.uri.rfind("/dev/", 0) == 0 || is_index(source.uri);
}

CameraRpe::~CameraRpe() {
  stop();
}

Status CameraRpe::start() {
  if (running_) return Status::ok();
  if (!open(impl_->capture, source_.uri))
    return {Errc::kUnavailable, "camera: cannot open the source"};
  running_ = true;
  thread_ = std::thread([this] { run(); });
  return Status::ok();
}

void CameraRpe::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
}

void CameraRpe::run() {
  cv::Mat frame;
  std::array<hal::RelativePoseDetection, limits::kMaxRpeDetectionsPerFrame> found;
  auto next_read = std::chrono::steady_clock::now();
  while (running_) {
    if (source_.min_period > Duration::zero()) {
      std::this_thread::sleep_until(next_read);
      next_read += source_.min_period;
    }
    if (!impl_->capture.isOpened() || !impl_->capture.read(frame) || frame.empty()) {
      // A device that went away (USB unplugged) is reopened, so is a file played in a loop; a
      // file's end is the end.
      const bool finished = !impl_->is_device && !source_.loop;
      {
        std::lock_guard lock(mutex_);
        ++stats_.read_failures;
        if (!finished) ++stats_.reopens;
      }
      impl_->capture.release();
      if (finished) break;
      if (impl_->is_device) std::this_thread::sleep_for(std::chrono::milliseconds(200));
      (void)open(impl_->capture, source_.uri);
      continue;
    }
    const TimePoint stamp = clock_.now() - source_.latency;
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t n = estimator_.detect(frame, stamp, found);
    const auto us =
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0)
            .count();
    std::lock_guard lock(mutex_);
    std::copy_n(found.begin(), n, latest_.begin());
    latest_count_ = n;
    ++latest_seq_;
    ++stats_.frames;
    stats_.longest_frame_us = std::max(stats_.longest_frame_us, static_cast<std::uint64_t>(us));
    counters_ = estimator_.counters();
  }
}

std::size_t CameraRpe::poll(std::span<hal::RelativePoseDetection> out) {
  std::lock_guard lock(mutex_);
  if (latest_seq_ == read_seq_) return 0;
  read_seq_ = latest_seq_;
  const std::size_t n = std::min(latest_count_, out.size());
  std::copy_n(latest_.begin(), n, out.begin());
  return n;
}

CameraStats CameraRpe::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

TagPoseCounters CameraRpe::detector_counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

}  // namespace colag::linux_hal
