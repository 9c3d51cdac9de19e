// The UAV's real PX4 and ROS 2 drivers (Cyclone DDS) against a Fast DDS process playing PX4's
// agent, FAST-LIO and the Livox driver with PX4's QoS: the two vendors match on the ROS 2 names
// and types, the arming sequence and the NED values arrive as PX4 expects them, and a peer that
// stops acknowledging or goes silent is reported.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>

#include "colag/hal/px4/px4_flight_controller.hpp"
#include "colag/hal/ros2/ros2_devices.hpp"
#include "colag/hal/scripted/scripted_devices.hpp"
#include "dds_test_env.hpp"

using namespace colag;
using namespace std::chrono_literals;
using State = hal::px4::OffboardSequencer::State;

namespace {

// A program of the test (the peer, uav_fw), its stdout and stderr in a file.
class Process {
 public:
  explicit Process(std::vector<std::string> args) {
    out_ = testing::TempDir() + "interop_" + std::to_string(getpid()) + "_" +
           std::to_string(++runs_) + ".log";
    std::vector<char*> argv;
    argv.reserve(args.size() + 1);
    for (std::string& a : args)
      argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    ok_ = posix_spawn(&pid_, argv[0], &fa, nullptr, argv.data(), environ) == 0;
    posix_spawn_file_actions_destroy(&fa);
  }
  ~Process() {
    if (pid_ > 0 && !waited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  bool started() const { return ok_; }
  void interrupt() const { kill(pid_, SIGINT); }
  // Waits for it to end; its output.
  std::string finish() {
    int status = 0;
    waitpid(pid_, &status, 0);
    waited_ = true;
    std::ifstream in(out_);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

 private:
  static inline int runs_ = 0;
  pid_t pid_ = 0;
  bool ok_ = false, waited_ = false;
  std::string out_;
};

// The Fast DDS peer for `duration_s`, with `extra` arguments.
Process peer_process(std::uint32_t domain, double duration_s,
                     const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {COLAG_FASTDDS_PEER_PATH, "--domain", std::to_string(domain),
                                   "--duration", std::to_string(duration_s)};
  args.insert(args.end(), extra.begin(), extra.end());
  return Process(args);
}

struct Firmware {
  explicit Firmware(std::uint32_t domain) : odometry(clock), lidar(clock) {
    hal::px4::Px4DriverConfig pc;
    pc.dds_domain = domain;
    std::string error;
    EXPECT_TRUE(px4.init(pc, error)) << error;
    hal::ros2::Ros2OdometryConfig oc;
    oc.dds_domain = domain;
    EXPECT_TRUE(odometry.init(oc, error)) << error;
    hal::ros2::Ros2LidarConfig lc;
    lc.dds_domain = domain;
    EXPECT_TRUE(lidar.init(lc, error)) << error;
  }
  // 50 Hz in real time (the peer runs on the wall clock), until `done` or `limit`.
  bool run_until(const std::function<bool()>& done, std::chrono::seconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
      clock.advance(20ms);
      status = px4.update(clock.now());
      hal::FlightSetpoint sp;
      sp.stamp = clock.now();
      sp.position_m = Vec3(1.0, 2.0, 1.5);  // 1 m east, 2 m north, 1.5 m up
      sp.yaw_rad = M_PI / 2;                // facing north
      (void)px4.send_setpoint(sp);
      hal::UavState s;
      if (odometry.poll(s)) lio = s;
      if (px4.poll(s)) px4_odometry = s;
      hal::LidarScanView scan;
      if (lidar.poll(scan)) returns = scan.points.size();
      if (done()) return true;
      std::this_thread::sleep_for(20ms);
    }
    return false;
  }

  hal::scripted::ManualClock clock;
  hal::px4::Px4FlightController px4;
  hal::ros2::Ros2Odometry odometry;
  hal::ros2::Ros2Lidar lidar;
  hal::FlightStatus status;
  hal::UavState lio, px4_odometry;
  std::size_t returns = 0;
};

}  // namespace

TEST(FastDdsInterop, ThePx4DriverArmsAndFliesAFastDdsPx4AndReadsItsOdometryAndClouds) {
  test::confine_dds_to_loopback();
  const std::uint32_t domain = test::private_domain_id();
  Firmware fw(domain);
  Process peer = peer_process(domain, 8.0);
  ASSERT_TRUE(peer.started());
  ASSERT_TRUE(fw.run_until([&] { return fw.px4.sequencer().state() == State::kInControl; }, 7s))
      << "state " << static_cast<int>(fw.px4.sequencer().state()) << ", statuses "
      << fw.px4.counters().statuses << ", acks " << fw.px4.counters().acks;
  // FAST-LIO's odometry and PX4's, both from the other vendor, and the clouds.
  ASSERT_TRUE(fw.run_until([&] { return fw.returns > 0 && fw.lio.stamp != TimePoint{}; }, 2s));
  EXPECT_NEAR((fw.px4_odometry.pose.p - Vec3(1.0, 2.0, 1.5)).norm(), 0.0, 1e-5);  // NED -> ENU
  EXPECT_NEAR(yaw_of(fw.px4_odometry.pose.q), M_PI / 2, 1e-5);                    // north
  EXPECT_NEAR((fw.lio.pose.p - Vec3(1.0, 2.0, 1.5)).norm(), 0.0, 1e-5);
  EXPECT_EQ(fw.returns, 100u);
  EXPECT_EQ(fw.lidar.counters().malformed, 0u);
  // Fly on for most of the peer's 8 s (it stays ours), then read what the peer saw.
  EXPECT_FALSE(fw.run_until([&] { return fw.status.state != msg::UavFlight::kInControl; }, 5s))
      << "fault " << static_cast<int>(fw.status.fault);
  const std::string out = peer.finish();
  // What PX4 received: position-only heartbeats at >= 10 Hz, the setpoint in NED (north, east,
  // down), yaw from north, DO_SET_MODE(1, 6) before ARM(1), addressed to system 1, external.
  EXPECT_NE(out.find("heartbeats not position-only: 0"), std::string::npos) << out;
  double hz = 0.0;
  const auto at = out.find(" Hz");
  ASSERT_NE(at, std::string::npos) << out;
  hz = std::stod(out.substr(out.rfind(": ", at) + 2));
  EXPECT_GE(hz, 10.0) << out;
  EXPECT_NE(out.find("last NED 2.000 1.000 -1.500 yaw 0.000"), std::string::npos) << out;
  EXPECT_NE(out.find("commands 176(1,6;sys 1 comp 1 ext 1) 400(1,0;sys 1 comp 1 ext 1)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("armed 1 nav_state 14"), std::string::npos) << out;
}

TEST(FastDdsInterop, APeerThatIgnoresCommandsIsAskedFiveTimesThenReported) {
  test::confine_dds_to_loopback();
  const std::uint32_t domain = test::private_domain_id();
  Firmware fw(domain);
  Process peer = peer_process(domain, 9.0, {"--ignore-commands"});
  ASSERT_TRUE(peer.started());
  // A second of stream, then DO_SET_MODE every second: no acknowledgement, no offboard.
  ASSERT_TRUE(fw.run_until([&] { return fw.status.state == msg::UavFlight::kLost; }, 8s))
      << "state " << static_cast<int>(fw.px4.sequencer().state());
  EXPECT_EQ(fw.status.fault, msg::FlightFault::kNoAck);
  EXPECT_EQ(fw.px4.counters().commands, 5u);
  const std::string out = peer.finish();
  EXPECT_EQ(out.find("400("), std::string::npos) << out;  // never asked to arm
  EXPECT_NE(out.find("armed 0 nav_state 4"), std::string::npos) << out;
}

TEST(FastDdsInterop, APeerThatFallsSilentEndsControlWithinItsTimeout) {
  test::confine_dds_to_loopback();
  const std::uint32_t domain = test::private_domain_id();
  Firmware fw(domain);
  Process peer = peer_process(domain, 8.0, {"--silent-after", "4"});
  ASSERT_TRUE(peer.started());
  ASSERT_TRUE(fw.run_until([&] { return fw.px4.sequencer().state() == State::kInControl; }, 4s));
  ASSERT_TRUE(fw.run_until([&] { return fw.status.state == msg::UavFlight::kLost; }, 5s));
  EXPECT_EQ(fw.status.fault, msg::FlightFault::kSilent);
  EXPECT_GT(fw.lio.stamp, TimePoint{});  // FAST-LIO (another process) went on
  (void)peer.finish();
}

// uav_fw itself, robot.hal px4, against the Fast DDS PX4: it takes off (no UGVs: it holds its
// altitude), and on SIGINT lands and waits for PX4 to disarm.
TEST(FastDdsInterop, UavFwTakesOffOnAFastDdsPx4AndLandsWhenStopped) {
  test::confine_dds_to_loopback();
  const std::uint32_t domain = test::private_domain_id();
  const std::string config = testing::TempDir() + "uav_px4_" + std::to_string(getpid()) + ".yaml";
  std::ofstream(config) << "robot: {id: 0, hal: px4}\n"
                        << "dds: {domain: " << domain + 1 << "}\n"
                        << "realtime: {fifo_priority: 0, lock_memory: false}\n"
                        << "px4: {release: '1.16', dds_domain: " << domain << "}\n"
                        << "camera: {device: sim}\n";
  Process peer = peer_process(domain, 12.0);
  Process uav({COLAG_UAV_FW_PATH, "--config", config});
  ASSERT_TRUE(peer.started() && uav.started());
  std::this_thread::sleep_for(7s);
  uav.interrupt();
  const std::string uav_out = uav.finish();
  const std::string out = peer.finish();
  EXPECT_NE(uav_out.find("px4: in control (offboard, armed)"), std::string::npos) << uav_out;
  EXPECT_NE(uav_out.find("uav_fw: landed and disarmed"), std::string::npos) << uav_out;
  EXPECT_NE(out.find("heartbeats not position-only: 0"), std::string::npos) << out;
  EXPECT_NE(out.find(" 21(0,0;sys 1 comp 1 ext 1)"), std::string::npos) << out;  // NAV_LAND
  EXPECT_NE(out.find("armed 0"), std::string::npos) << out;
  // Its setpoint: its flight altitude (1 m up is NED z -1).
  const auto at = out.find("last NED ");
  ASSERT_NE(at, std::string::npos) << out;
  std::istringstream ned(out.substr(at + 9));
  double n = 0, e = 0, d = 0;
  ned >> n >> e >> d;
  EXPECT_LT(d, -0.5) << out;
}
