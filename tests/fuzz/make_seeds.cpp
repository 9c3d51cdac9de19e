// Writes the fuzzers' seed corpora (tests/fuzz/corpus/<fuzzer>/) from the real encoders, so the
// fuzzers start from well-formed inputs: `colag_fuzz_seeds tests/fuzz/corpus`. The corpora are in
// the repository; rerun this after changing a wire format.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "colag/common/map_patch_codec.hpp"
#include "colag/hal/can/wheel_protocol.hpp"
#include "colag/platform/dds/convert.hpp"
#include "dds/ddsi/ddsi_cdrstream.h"

namespace fs = std::filesystem;
using namespace colag;
using Bytes = std::vector<std::uint8_t>;

namespace {

void write(const fs::path& dir, const std::string& name, const Bytes& bytes) {
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}
void put16(Bytes& b, std::uint16_t v) {
  b.push_back(static_cast<std::uint8_t>(v));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
}

// fuzz_map_patch: encoding, width, height, origin cell x/y, flags, payload.
void map_patch_seeds(const fs::path& dir) {
  const auto emit = [&](const std::string& name, const PatchCells& cells, std::int16_t cx,
                        std::int16_t cy) {
    msg::MapPatch p;
    if (!encode_patch(cells, p)) return;
    Bytes b{static_cast<std::uint8_t>(p.encoding)};
    put16(b, p.width_cells);
    put16(b, p.height_cells);
    put16(b, static_cast<std::uint16_t>(cx));
    put16(b, static_cast<std::uint16_t>(cy));
    b.push_back(0);
    b.insert(b.end(), p.data.items, p.data.items + p.data.count);
    write(dir, name, b);
  };
  PatchCells c;
  c.width = c.height = 50;
  for (auto& s : c.cells)
    s = CellState::kFree;
  emit("free_50x50", c, 100, 100);
  for (int y = 10; y < 19; ++y)
    for (int x = 20; x < 29; ++x)
      c.cells[static_cast<std::size_t>(y * 50 + x)] = CellState::kOccupied;
  emit("one_box", c, 120, 40);
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < 50; ++x)
      if ((x * 7 + y * 3) % 5 == 0)
        c.cells[static_cast<std::size_t>(y * 50 + x)] = CellState::kUnknown;
  emit("mixed_packed", c, 0, 0);
  c.width = 64;
  c.height = 1;
  emit("one_row", c, 5, 200);
}

// fuzz_can_frames: a layout byte, then frames of (time step us, id | flags, dlc, data).
void can_seeds(const fs::path& dir) {
  const hal::can::WheelProtocolConfig cfg;
  const auto frame = [](Bytes& b, std::uint16_t dt_us, const hal::CanFrame& f) {
    put16(b, dt_us);
    put16(b, static_cast<std::uint16_t>(f.id));
    b.push_back(f.dlc);
    b.insert(b.end(), f.data, f.data + 8);
  };
  Bytes drive{0};
  std::uint32_t left = 0, right = 0;
  for (std::uint8_t i = 0; i < 40; ++i) {
    left = (left + 52) % hal::can::kTickModulus;
    right = (right + 60) % hal::can::kTickModulus;
    frame(drive, 20000, hal::can::encode(hal::can::EncoderCounts{left, right, i}, cfg));
    if (i % 2 == 0) frame(drive, 100, hal::can::encode(hal::can::WheelSpeeds{200, 230, i}, cfg));
  }
  write(dir, "drive_40_frames", drive);
  Bytes wrap{0};
  left = hal::can::kTickModulus - 100;
  for (std::uint8_t i = 250; i != 10; ++i) {
    left = (left + 40) % hal::can::kTickModulus;
    frame(wrap, 20000, hal::can::encode(hal::can::EncoderCounts{left, 7, i}, cfg));
  }
  write(dir, "tick_and_alive_wrap", wrap);
  Bytes command{0};
  frame(command, 20000, hal::can::encode(hal::can::SpeedCommand{300, -300, true, 3}, cfg));
  write(dir, "command_echo", command);
}

// fuzz_idl_sample: topic byte, then the XCDR1 little-endian body Cyclone DDS writes.
template <class Msg>
void idl_seed(const fs::path& dir, const std::string& name, const Msg& m) {
  using namespace platform::dds;
  auto* sample = new IdlSample<Msg>;
  to_idl(m, *sample);
  dds_ostream_t os;
  dds_ostream_init(&os, 0, 1);
  dds_stream_write(&os, reinterpret_cast<const char*>(&sample->sample), descriptor<Msg>().m_ops);
  Bytes b{static_cast<std::uint8_t>(msg::topic_of<Msg>)};
  b.insert(b.end(), os.m_buffer, os.m_buffer + os.m_index);
  dds_ostream_fini(&os);
  delete sample;
  write(dir, name, b);
}

void idl_seeds(const fs::path& dir) {
  const TimePoint t{std::chrono::seconds(12)};
  msg::UavOdometry odo;
  odo.stamp = t;
  odo.uav_id = 100;
  odo.position_m[2] = 1.5;
  idl_seed(dir, "uav_odometry", odo);
  msg::RelativePose rpe;
  rpe.stamp = t;
  rpe.uav_id = 100;
  rpe.ugv_id = 2;
  rpe.position_m[2] = -1.4;
  rpe.covariance[0] = rpe.covariance[5] = 0.04;
  idl_seed(dir, "relative_pose", rpe);
  auto* patch = new msg::MapPatch;
  PatchCells cells;
  cells.width = cells.height = 30;
  for (auto& s : cells.cells)
    s = CellState::kFree;
  cells.cells[40] = CellState::kOccupied;
  if (encode_patch(cells, *patch)) {
    patch->stamp = t;
    patch->ugv_id = 3;
    patch->resolution_m = 0.1;
    idl_seed(dir, "map_patch", *patch);
  }
  delete patch;
  msg::CollisionInfo ci;
  ci.stamp = t;
  ci.ugv_id = 1;
  ci.time_to_collision_s = 4.0;
  idl_seed(dir, "collision_info", ci);
  msg::UgvStatus st;
  st.stamp = t;
  st.ugv_id = 4;
  st.mode = msg::UgvMode::kDriving;
  idl_seed(dir, "ugv_status", st);
  auto* plan = new msg::SupportPlan;
  plan->stamp = t;
  plan->stops.count = 3;
  for (int i = 0; i < 3; ++i)
    plan->stops[i].ugv_id = static_cast<RobotId>(i + 1);
  idl_seed(dir, "support_plan", *plan);
  delete plan;
}

void pcd_seeds(const fs::path& dir) {
  const std::string ascii =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
      "WIDTH 4\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n"
      "0 0 0.3\n0.05 0 0.6\n3 3 0.0\n-2 1 0.5\n";
  write(dir, "ascii_4_points", Bytes(ascii.begin(), ascii.end()));
  std::string binary =
      "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
      "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA binary\n";
  const float pts[3][4] = {{1, 1, 0.5f, 7}, {1.05f, 1, 0.6f, 7}, {-4, 2, 0.2f, 1}};
  binary.append(reinterpret_cast<const char*>(pts), sizeof(pts));
  write(dir, "binary_3_points", Bytes(binary.begin(), binary.end()));
  const std::string doubles =
      "VERSION 0.7\nFIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\n"
      "POINTS 1\nDATA ascii\n1.5 -2.5 0.6\n";
  write(dir, "ascii_doubles", Bytes(doubles.begin(), doubles.end()));
}

void yaml_seeds(const fs::path& dir, const fs::path& config_dir) {
  for (const auto& [file, selector] : {std::pair{"ugv.example.yaml", 1},
                                       {"ugv_odrive.example.yaml", 1},
                                       {"ugv_agilex.example.yaml", 1},
                                       {"uav.example.yaml", 0}}) {
    std::ifstream in(config_dir / file, std::ios::binary);
    std::string text(std::istreambuf_iterator<char>(in), {});
    // The fuzzer skips documents naming device files: use a video file instead of /dev/video0.
    if (const auto at = text.find("/dev/video0"); at != std::string::npos)
      text.replace(at, 11, "video0.mp4");
    Bytes b{static_cast<std::uint8_t>(selector)};
    b.insert(b.end(), text.begin(), text.end());
    write(dir, file, b);
  }
  const std::string flow = "\x01{robot: {id: 3, goal: [1, -16]}, can: {interface: vcan0}}";
  write(dir, "ugv_flow_style", Bytes(flow.begin(), flow.end()));
}

// fuzz_tsptw: instances in the benchmark sets' text format.
void tsptw_seeds(const fs::path& dir) {
  const std::string six =
      "# depot + 5 customers\n6\n0 10 17 14 22 9\n10 0 11 15 13 18\n17 11 0 9 8 22\n"
      "14 15 9 0 14 13\n22 13 8 14 0 25\n9 18 22 13 25 0\n0 200\n0 30\n20 60\n40 80\n"
      "30 70\n60 120\n";
  write(dir, "six_nodes", Bytes(six.begin(), six.end()));
  const std::string two = "2\n0 1.5\n1.5 0\n0 1e9\n0 0.5\n";
  write(dir, "two_nodes_late", Bytes(two.begin(), two.end()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: colag_fuzz_seeds CORPUS_DIR CONFIG_DIR (tests/fuzz/corpus config)\n";
    return 2;
  }
  const fs::path out = argv[1];
  map_patch_seeds(out / "map_patch");
  can_seeds(out / "can_frames");
  idl_seeds(out / "idl_sample");
  pcd_seeds(out / "pcd");
  yaml_seeds(out / "yaml_config", argv[2]);
  tsptw_seeds(out / "tsptw");
  std::cout << "seed corpora written under " << out << "\n";
  return 0;
}
