#include "colag/sim/mission_png.hpp"

#include <Eigen/Eigenvalues>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace colag::programs {

namespace {
const cv::Scalar kPalette[] = {{200, 80, 20}, {30, 140, 30}, {20, 110, 230}, {170, 40, 170},
                               {0, 160, 190}, {120, 90, 30}, {90, 90, 200},  {30, 170, 120}};

cv::Scalar colour(std::size_t i) {
  return kPalette[i % (sizeof kPalette / sizeof kPalette[0])];
}

// The part of the world drawn (the arena, every path and goal, with a margin) and its scale: the
// longer side is 800 px whatever the map's size or shape, so nothing is cropped.
class View {
 public:
  explicit View(const mission::MissionTrace& t) {
    lo_ = Vec2(t.world.min_x_m, t.world.min_y_m);
    hi_ = Vec2(t.world.max_x_m, t.world.max_y_m);
    const auto take = [&](const Vec2& p) {
      lo_ = lo_.cwiseMin(p);
      hi_ = hi_.cwiseMax(p);
    };
    for (const auto& path : t.ugv_paths)
      for (const auto& s : path)
        take(s.truth);
    for (const Vec2& g : t.goals)
      take(g);
    for (const auto& route : t.vias)
      for (const Vec2& v : route)
        take(v);
    for (const auto& path : t.uav_paths)
      for (const Vec2& p : path)
        take(p);
    lo_ -= Vec2(1.0, 1.0);
    hi_ += Vec2(1.0, 1.0);
    scale_ = 800.0 / std::max(hi_.x() - lo_.x(), hi_.y() - lo_.y());
  }
  cv::Point px(const Vec2& p) const {
    return {kMargin + static_cast<int>(std::lround((p.x() - lo_.x()) * scale_)),
            kMargin / 2 + static_cast<int>(std::lround((hi_.y() - p.y()) * scale_))};
  }
  double scale() const { return scale_; }  // pixels per metre
  int width() const { return px(Vec2(hi_.x(), lo_.y())).x + kMargin / 2; }
  int map_bottom() const { return px(lo_).y; }
  const Vec2& lo() const { return lo_; }
  const Vec2& hi() const { return hi_; }
  static constexpr int kMargin = 50;  // room for the axes' labels

 private:
  Vec2 lo_, hi_;
  double scale_ = 1.0;
};

// Ticks and labels in metres along the bottom and left edges, a round step of ~100 px.
void draw_axes(cv::Mat& img, const View& v) {
  double step = 1.0;
  for (const double s : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0}) {
    step = s;
    if (s * v.scale() >= 80.0) break;
  }
  const cv::Scalar grey(150, 150, 150);
  const auto label = [&](const cv::Point& at, double metres) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", metres);
    cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.4, grey, 1, cv::LINE_AA);
  };
  const int bottom = v.map_bottom();
  for (double x = std::ceil(v.lo().x() / step) * step; x <= v.hi().x(); x += step) {
    const cv::Point p = v.px(Vec2(x, v.lo().y()));
    cv::line(img, {p.x, bottom}, {p.x, bottom + 6}, grey, 1);
    label({p.x - 8, bottom + 20}, x);
  }
  for (double y = std::ceil(v.lo().y() / step) * step; y <= v.hi().y(); y += step) {
    const cv::Point p = v.px(Vec2(v.lo().x(), y));
    cv::line(img, {View::kMargin - 6, p.y}, {View::kMargin, p.y}, grey, 1);
    label({4, p.y + 4}, y);
  }
  cv::putText(img, "m", {v.width() - 20, bottom + 20}, cv::FONT_HERSHEY_SIMPLEX, 0.4, grey, 1,
              cv::LINE_AA);
}

}  // namespace

bool draw_mission(const mission::MissionTrace& t, const mission::MissionOutcome& o,
                  const std::string& path, std::string& error) {
  const View view(t);
  const auto px = [&](const Vec2& p) { return view.px(p); };
  const double scale = view.scale();
  const int legend = 180;
  const int caption_top = view.map_bottom() + 30;
  // At least as wide as the caption's longest line, however narrow the map.
  cv::Mat img(caption_top + legend, std::max(view.width(), 760), CV_8UC3,
              cv::Scalar(255, 255, 255));
  draw_axes(img, view);
  // What the UAV never saw at ground level.
  const int cell = std::max(1, static_cast<int>(std::ceil(0.1 * scale)));  // no gaps
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
  for (const auto& flown : t.uav_paths) {  // each UAV's, in black
    for (std::size_t i = 1; i < flown.size(); ++i)
      cv::line(img, px(flown[i - 1]), px(flown[i]), cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
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
      const cv::Size axes(std::max(1, static_cast<int>(3.0 * std::sqrt(l(1)) * scale)),
                          std::max(1, static_cast<int>(3.0 * std::sqrt(l(0)) * scale)));
      cv::ellipse(img, px(e.centre), axes, angle, 0, 360, c, 1, cv::LINE_AA);
    }
    if (!samples.empty()) cv::circle(img, px(samples.front().truth), 5, c, 2);
    if (u < t.goals.size()) cv::drawMarker(img, px(t.goals[u]), c, cv::MARKER_SQUARE, 10, 2);
    if (u < t.vias.size())
      for (const Vec2& v : t.vias[u])
        cv::drawMarker(img, px(v), c, cv::MARKER_DIAMOND, 8, 1);
  }
  for (const auto& s : t.support_points) {
    cv::drawMarker(img, px(s.point), colour(static_cast<std::size_t>(s.ugv)),
                   cv::MARKER_TILTED_CROSS, 9, 2);
  }
  for (const Vec2& c : t.collisions)
    cv::circle(img, px(c), 9, cv::Scalar(0, 0, 255), cv::FILLED);

  // Legend and metrics.
  const int y0 = caption_top + 12;
  const auto text = [&](int x, int y, const std::string& str, const cv::Scalar& c = {0, 0, 0}) {
    cv::putText(img, str, {x, y}, cv::FONT_HERSHEY_SIMPLEX, 0.5, c, 1, cv::LINE_AA);
  };
  char line[256];
  std::snprintf(
      line, sizeof line, "%s map, %zu UGV%s, seed %llu, ablation %s%s",
      o.config.scenario == "file" ? o.config.map_file.c_str() : o.config.scenario.c_str(),
      o.ugvs.size(), o.ugvs.size() == 1 ? "" : "s", static_cast<unsigned long long>(o.config.seed),
      mission::to_string(o.config.ablation), o.config.self_perception ? ", self-perception" : "");
  text(10, y0, line);
  char reach[32];
  std::snprintf(reach, sizeof reach, o.reach_time_s >= 0.0 ? "%.1f s" : "- (none reached)",
                o.reach_time_s);
  std::snprintf(line, sizeof line,
                "reach %s   waiting %.2f s (max %.2f)   UGV path %.1f m   UAV path %.1f m", reach,
                o.waiting_time_s, o.max_waiting_time_s, o.ugv_traj_length_m, o.uav_traj_length_m);
  text(10, y0 + 22, line);
  std::snprintf(
      line, sizeof line, "collisions %d   %s", o.collisions,
      o.all_reached ? "all UGVs reached their goals" : "NOT all UGVs reached their goals");
  text(10, y0 + 44, line,
       o.collisions > 0 || !o.all_reached ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 0, 0));
  text(10, y0 + 70, "thick line: true UGV path   dots: its estimate   ellipses: 3-sigma every 5 s");
  text(10, y0 + 92,
       "x: support point   black line: UAV   dark squares: obstacles   red: collision");
  text(10, y0 + 114,
       "light grey: never seen by the UAV   circle: start   square: goal   diamond: route point");
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
