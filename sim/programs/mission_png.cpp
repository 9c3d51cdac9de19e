#include "mission_png.hpp"

#include <Eigen/Eigenvalues>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace colag::programs {

namespace {
constexpr double kScale = 22.0;  // pixels per metre
constexpr double kHalf = 18.0;   // metres shown either side of the origin
const cv::Scalar kPalette[] = {{200, 80, 20}, {30, 140, 30}, {20, 110, 230}, {170, 40, 170},
                               {0, 160, 190}, {120, 90, 30}, {90, 90, 200},  {30, 170, 120}};

cv::Point px(const Vec2& p) {
  return {static_cast<int>(std::lround((p.x() + kHalf) * kScale)),
          static_cast<int>(std::lround((kHalf - p.y()) * kScale))};
}
cv::Scalar colour(std::size_t i) {
  return kPalette[i % (sizeof kPalette / sizeof kPalette[0])];
}
}  // namespace

bool draw_mission(const mission::MissionTrace& t, const mission::MissionOutcome& o,
                  const std::string& path, std::string& error) {
  const int side = static_cast<int>(2 * kHalf * kScale);
  const int legend = 150;
  cv::Mat img(side + legend, side, CV_8UC3, cv::Scalar(255, 255, 255));
  // What the UAV never saw at ground level.
  const int cell = std::max(1, static_cast<int>(std::lround(0.1 * kScale)));
  for (const Vec2& u : t.unknown_cells) {
    const cv::Point c = px(u);
    cv::rectangle(img, {c.x - cell / 2, c.y - cell / 2, cell, cell}, cv::Scalar(225, 225, 225),
                  cv::FILLED);
  }
  cv::rectangle(img, px(Vec2(t.world.min_x_m, t.world.max_y_m)),
                px(Vec2(t.world.max_x_m, t.world.min_y_m)), cv::Scalar(180, 180, 180), 1);
  for (const auto& b : t.world.boxes) {
    cv::rectangle(img, px(b.center + Vec2(-b.half_size.x(), b.half_size.y())),
                  px(b.center + Vec2(b.half_size.x(), -b.half_size.y())), cv::Scalar(70, 70, 70),
                  cv::FILLED);
  }
  for (std::size_t i = 1; i < t.uav_path.size(); ++i) {
    cv::line(img, px(t.uav_path[i - 1]), px(t.uav_path[i]), cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  for (std::size_t u = 0; u < t.ugv_paths.size(); ++u) {
    const cv::Scalar c = colour(u);
    const auto& samples = t.ugv_paths[u];
    for (std::size_t i = 1; i < samples.size(); ++i) {
      cv::line(img, px(samples[i - 1].truth), px(samples[i].truth), c, 2, cv::LINE_AA);
    }
    for (const auto& s : samples) {
      if (s.initialised) cv::circle(img, px(s.estimate), 1, c, cv::FILLED);
    }
    for (const auto& e : t.ugv_ellipses[u]) {
      Eigen::SelfAdjointEigenSolver<Mat2> eig(0.5 * (e.covariance + e.covariance.transpose()));
      const Vec2 l = eig.eigenvalues().cwiseMax(0.0);
      const Vec2 major = eig.eigenvectors().col(1);
      const double angle = -std::atan2(major.y(), major.x()) * 180.0 / M_PI;
      const cv::Size axes(std::max(1, static_cast<int>(3.0 * std::sqrt(l(1)) * kScale)),
                          std::max(1, static_cast<int>(3.0 * std::sqrt(l(0)) * kScale)));
      cv::ellipse(img, px(e.centre), axes, angle, 0, 360, c, 1, cv::LINE_AA);
    }
    if (!samples.empty()) cv::circle(img, px(samples.front().truth), 5, c, 2);
    if (u < t.goals.size()) cv::drawMarker(img, px(t.goals[u]), c, cv::MARKER_SQUARE, 10, 2);
  }
  for (const auto& s : t.support_points) {
    cv::drawMarker(img, px(s.point), colour(static_cast<std::size_t>(s.ugv)),
                   cv::MARKER_TILTED_CROSS, 9, 2);
  }
  for (const Vec2& c : t.collisions)
    cv::circle(img, px(c), 9, cv::Scalar(0, 0, 255), cv::FILLED);

  // Legend and metrics.
  const int y0 = side + 22;
  const auto text = [&](int x, int y, const std::string& str, const cv::Scalar& c = {0, 0, 0}) {
    cv::putText(img, str, {x, y}, cv::FONT_HERSHEY_SIMPLEX, 0.5, c, 1, cv::LINE_AA);
  };
  char line[256];
  std::snprintf(line, sizeof line, "%s map, %zu UGVs, seed %llu, ablation %s%s",
                o.config.scenario == "file" ? o.config.map_file.c_str() : o.config.scenario.c_str(),
                o.ugvs.size(), static_cast<unsigned long long>(o.config.seed),
                mission::to_string(o.config.ablation),
                o.config.self_perception ? ", self-perception" : "");
  text(10, y0, line);
  std::snprintf(line, sizeof line,
                "reach %.1f s   waiting %.2f s (max %.2f)   UGV path %.1f m   UAV path %.1f m",
                o.reach_time_s, o.waiting_time_s, o.max_waiting_time_s, o.ugv_traj_length_m,
                o.uav_traj_length_m);
  text(10, y0 + 22, line);
  std::snprintf(
      line, sizeof line, "collisions %d   %s", o.collisions,
      o.all_reached ? "all UGVs reached their goals" : "NOT all UGVs reached their goals");
  text(10, y0 + 44, line,
       o.collisions > 0 || !o.all_reached ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 0, 0));
  text(10, y0 + 70, "thick line: true UGV path   dots: its estimate   ellipses: 3-sigma every 5 s");
  text(10, y0 + 92,
       "x: support point   black line: UAV   dark squares: obstacles   red: collision");
  text(10, y0 + 114, "light grey: never seen by the UAV   circle: start   square: goal");
  try {
    if (!cv::imwrite(path, img)) {
      error = "cannot write " + path;
      return false;
    }
  } catch (const cv::Exception& e) {  // host program: OpenCV reports failures by exception
    error = "cannot write " + path + ": " + e.what();
    return false;
  }
  return true;
}

}  // namespace colag::programs
