#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "colag/common/random.hpp"
#include "colag/common/ugv_ekf.hpp"

using namespace colag;
using namespace std::chrono_literals;

namespace {

constexpr Duration kOdomPeriod = 20ms;  // 50 Hz

Mat3 rpe_covariance() {
  return Vec3(0.2 * 0.2, 0.2 * 0.2, 0.05 * 0.05).asDiagonal();
}

// Exactly the filter's noise model, without the slip terms, so the simulation matches it; the
// wheels exactly calibrated and the measurements' covariance honest (the paper's 3-state EKF).
UgvEkfConfig white_noise_config() {
  UgvEkfConfig c;
  c.noise.sigma_v_fraction = 0.0;
  c.noise.sigma_omega_fraction = 0.0;
  c.calibration.estimate = false;
  c.adapt_measurement_noise = false;
  c.frame_walk_m_per_sqrt_s = 0.0;  // located in a frame fixed to the ground
  c.start_window_s = 0.0;           // the first relative pose starts it (see StartsFrom...)
  return c;
}

// The robot stands for `d`: odometry of no motion at 50 Hz, `t` moved on.
void stand_still(UgvEkf& ekf, TimePoint& t, Duration d) {
  for (const TimePoint end = t + d; t < end;) {
    t += kOdomPeriod;
    ASSERT_TRUE(ekf.predict(t, 0.0, 0.0));
  }
}

// The defaults, but started from the first relative pose.
UgvEkfConfig one_shot() {
  UgvEkfConfig c;
  c.start_window_s = 0.0;
  return c;
}

struct Truth {
  Vec3 x = Vec3(1.0, 2.0, 0.3);
  void step(double v, double w, double dt) {
    x.x() += std::cos(x.z()) * v * dt;
    x.y() += std::sin(x.z()) * v * dt;
    x.z() = wrap_angle(x.z() + w * dt);
  }
};

PoseMeasurement measure(const Truth& truth, TimePoint t, Rng& rng) {
  return {t,
          {Vec2(truth.x.x() + rng.gaussian(0, 0.2), truth.x.y() + rng.gaussian(0, 0.2)),
           wrap_angle(truth.x.z() + rng.gaussian(0, 0.05))},
          rpe_covariance()};
}

double nees(const Truth& truth, const UgvEkf& ekf) {
  Vec3 e = truth.x - ekf.mean();
  e.z() = wrap_angle(e.z());
  return e.dot(ekf.covariance().ldlt().solve(e));
}

// Average NEES at each whole second over `runs` Monte-Carlo runs of 30 s; RPE once a second.
std::vector<double> monte_carlo_nees(double v, double w, int runs) {
  const int seconds = 30;
  std::vector<double> sum(seconds, 0.0);
  const OdometryNoise noise = white_noise_config().noise;
  for (int r = 0; r < runs; ++r) {
    Rng rng(1000 + r);
    UgvEkf ekf(white_noise_config());
    Truth truth;
    TimePoint t{};
    EXPECT_EQ(ekf.update(measure(truth, t, rng)), UgvEkf::Update::kInitialized);
    for (int s = 0; s < seconds; ++s) {
      for (int k = 0; k < 50; ++k) {
        t += kOdomPeriod;
        truth.step(v, w, to_seconds(kOdomPeriod));
        EXPECT_TRUE(ekf.predict(t, v + rng.gaussian(0, noise.sigma_v_mps),
                                w + rng.gaussian(0, noise.sigma_omega_radps)));
      }
      sum[s] += nees(truth, ekf);  // before this second's measurement: covariance at its widest
      ekf.update(measure(truth, t, rng));
    }
  }
  for (double& x : sum)
    x /= runs;
  return sum;
}

void expect_consistent(const std::vector<double>& mean_nees) {
  // chi2(300) 2.5 % and 97.5 % quantiles / 100 runs: the 95 % band of the average NEES, 3 dof.
  const double lo = 2.54, hi = 3.50;
  int inside = 0;
  double total = 0;
  for (double m : mean_nees) {
    inside += m >= lo && m <= hi;
    total += m;
  }
  EXPECT_GE(inside, static_cast<int>(0.9 * static_cast<double>(mean_nees.size())))
      << "average NEES outside the 95 % band too often";
  EXPECT_NEAR(total / static_cast<double>(mean_nees.size()), 3.0, 0.3);
}

}  // namespace

TEST(UgvEkf, ConsistentOnAStraightLine) {
  expect_consistent(monte_carlo_nees(0.5, 0.0, 100));
}

TEST(UgvEkf, ConsistentOnACircle) {
  expect_consistent(monte_carlo_nees(0.5, 0.2, 100));
}

namespace {

// Wheels with a calibration error drawn from the filter's own prior (so that a Bayesian filter
// must be consistent), driven along a weaving path (turn rate up to `turn_radps`), the pose
// measured twice a second. Returns the mean NEES over the runs and the last 40 s of each;
// `state_error` the mean absolute error of calibration state `state` at the end.
// `truth_turn_walk`: how far the true turn scale and slip wander per sqrt(radian turned).
double calibration_monte_carlo(const UgvEkfConfig& filter, int runs, double& state_error,
                               int state = kWPerMetre, double turn_radps = 0.4,
                               double truth_turn_walk = 0.0) {
  const UgvEkfConfig truth_model = [] {
    UgvEkfConfig c = white_noise_config();
    c.calibration.estimate = true;
    return c;
  }();
  const Eigen::Matrix<double, kCalibrationDim, 1> prior_sigma =
      truth_model.calibration.prior_variance().cwiseSqrt();
  const OdometryNoise noise = truth_model.noise;
  double nees_sum = 0.0;
  int nees_n = 0;
  state_error = 0.0;
  for (int r = 0; r < runs; ++r) {
    Rng rng(7000 + r);
    UgvStateVec truth = UgvStateVec::Zero();
    truth.head<3>() = Vec3(1.0, 2.0, 0.3);
    for (int k = 0; k < kCalibrationDim; ++k)
      truth(kPoseDim + k) = rng.gaussian(0.0, prior_sigma(k));
    UgvEkf ekf(filter);
    TimePoint t{};
    const auto measure_truth = [&] {
      return PoseMeasurement{
          t,
          {Vec2(truth.x() + rng.gaussian(0, 0.2), truth.y() + rng.gaussian(0, 0.2)),
           wrap_angle(truth(2) + rng.gaussian(0, 0.05))},
          rpe_covariance()};
    };
    EXPECT_EQ(ekf.update(measure_truth()), UgvEkf::Update::kInitialized);
    for (int step = 1; step <= 60 * 50; ++step) {
      t += kOdomPeriod;
      const double time = to_seconds(t - TimePoint{});
      const double v = 0.4, w = turn_radps * std::sin(0.25 * time);
      // The robot moves by the calibrated twist; the encoders measure it with white noise.
      const Eigen::Vector2d true_twist = calibrated_twist(truth, v, w);
      const double wander = truth_turn_walk * std::sqrt(std::abs(w) * 0.02);
      truth(kScaleW) += rng.gaussian(0.0, wander);
      truth(kSlip) += rng.gaussian(0.0, wander);
      truth(0) += std::cos(truth(2)) * true_twist(0) * 0.02;
      truth(1) += std::sin(truth(2)) * true_twist(0) * 0.02;
      truth(2) = wrap_angle(truth(2) + true_twist(1) * 0.02);
      EXPECT_TRUE(ekf.predict(t, v + rng.gaussian(0, noise.sigma_v_mps),
                              w + rng.gaussian(0, noise.sigma_omega_radps)));
      if (step % 25 != 0) continue;
      if (time >= 20.0) {
        Vec3 e = truth.head<3>() - ekf.mean();
        e.z() = wrap_angle(e.z());
        nees_sum += e.dot(ekf.covariance().ldlt().solve(e));
        ++nees_n;
      }
      ekf.update(measure_truth());
    }
    state_error += std::abs(ekf.state()(state) - truth(state)) / runs;
  }
  return nees_sum / nees_n;
}

}  // namespace

TEST(UgvEkf, LearnsTheWheelCalibrationAndStaysConsistent) {
  UgvEkfConfig filter = white_noise_config();
  filter.calibration.estimate = true;
  filter.calibration.walk_turn_per_sqrt_rad = 0.0;  // these wheels keep their calibration
  double drift_error = 0.0;
  const double nees = calibration_monte_carlo(filter, 40, drift_error);
  EXPECT_GT(nees, 2.4);
  EXPECT_LT(nees, 3.8);
  // Prior sigma 0.1 rad/m: a minute of driving learns it to a fraction of that (0.017).
  EXPECT_LT(drift_error, 0.03);  // 0.088 without calibration states
}

TEST(UgvEkf, WithoutCalibrationStatesTheSameWheelsMakeItOverConfident) {
  double drift_error = 0.0;
  const double nees = calibration_monte_carlo(white_noise_config(), 40, drift_error);
  EXPECT_GT(nees, 10.0);  // what the paper's 3-state filter does with real wheels
}

// A skid-steer robot turning up to 1.2 rad/s (as on the spot): its slip is learnt, and a filter
// that only has the constant turn scale cannot stay consistent on the same wheels.
TEST(UgvEkf, LearnsSkidSteerSlipThatGrowsWithTheTurnRate) {
  UgvEkfConfig filter = white_noise_config();
  filter.calibration.estimate = true;
  filter.calibration.walk_turn_per_sqrt_rad = 0.0;  // the same ground under every turn
  double slip_error = 0.0;
  const double nees = calibration_monte_carlo(filter, 40, slip_error, kSlip, 1.2);
  EXPECT_GT(nees, 2.4);  // 2.56
  EXPECT_LT(nees, 3.8);
  EXPECT_LT(slip_error, 0.04);  // 0.016; prior sigma 0.1 per rad/s

  filter.calibration.sigma_slip_per_radps = 0.0;
  filter.calibration.walk_slip_per_sqrt_s = 0.0;
  EXPECT_GT(calibration_monte_carlo(filter, 40, slip_error, kSlip, 1.2), 4.5);  // 7.7
}

// The ground differs under each turn: the true turn scale and slip wander as the robot turns.
// A filter sure that what the last turns taught holds for the next grows over-confident; the
// default turn walk keeps it consistent.
TEST(UgvEkf, StaysConsistentWhenTheSlipChangesFromTurnToTurn) {
  UgvEkfConfig filter = white_noise_config();
  filter.calibration.estimate = true;
  const double ground = filter.calibration.walk_turn_per_sqrt_rad;  // as much as it assumes
  ASSERT_GT(ground, 0.0);
  double error = 0.0;
  const double nees = calibration_monte_carlo(filter, 40, error, kSlip, 1.2, ground);
  EXPECT_GT(nees, 2.2);
  EXPECT_LT(nees, 4.2);  // 3.50
  filter.calibration.walk_turn_per_sqrt_rad = 0.0;
  EXPECT_GT(calibration_monte_carlo(filter, 40, error, kSlip, 1.2, ground), 20.0);  // 268
}

TEST(UgvEkf, ScalesAnUnderReportedMeasurementCovarianceAndOnlyThat) {
  for (const double truth_scale : {1.0, 1.5}) {
    UgvEkfConfig cfg = white_noise_config();
    cfg.adapt_measurement_noise = true;
    UgvEkf ekf(cfg);
    Rng rng(11);
    TimePoint t{};
    for (int k = 0; k < 400; ++k) {
      t += 500ms;
      // Standing still: the measurement is all the filter learns from.
      const PoseMeasurement z{
          t,
          {Vec2(rng.gaussian(0, 0.2 * truth_scale), rng.gaussian(0, 0.2 * truth_scale)),
           rng.gaussian(0, 0.05 * truth_scale)},
          rpe_covariance()};
      ASSERT_TRUE(ekf.predict(t, 0.0, 0.0));
      (void)ekf.update(z);
    }
    if (truth_scale == 1.0) {
      EXPECT_LT(ekf.measurement_noise_scale(), 1.4);
    } else {  // variance 2.25 x the reported
      EXPECT_GT(ekf.measurement_noise_scale(), 1.7);
      EXPECT_LT(ekf.measurement_noise_scale(), 3.0);
    }
  }
}

TEST(UgvEkf, CovarianceGrowthMatchesTheClosedFormOnAStraightLine) {
  UgvEkf ekf(white_noise_config());
  ASSERT_EQ(ekf.update({TimePoint{}, {Vec2(0, 0), 0.0}, Mat3::Identity() * 1e-14}),
            UgvEkf::Update::kInitialized);
  const double v = 0.5, dt = 0.02;
  const double sv = 0.0336, sw = 0.0292;
  const int n = 500;
  for (int k = 1; k <= n; ++k)
    ASSERT_TRUE(ekf.predict(TimePoint{k * kOdomPeriod}, v, 0.0));
  // With yaw = 0: P_xx = n sv^2 dt^2, P_tt = n q, P_yt = v dt q n(n-1)/2,
  // P_yy = v^2 dt^2 q (n-1) n (2n-1) / 6, with q = sw^2 dt^2 (the linearised model);
  // along the path (x) the heading's second-order shortfall adds sqrt(3)/2 P_tt v dt to the
  // standard deviation at each step: sqrt(P_xx) between its sum and the sum plus the
  // first-order sqrt(n) sv dt.
  const double q = sw * sw * dt * dt;
  const Mat3 P = ekf.covariance();
  const double shortfall = 0.5 * std::sqrt(3.0) * v * dt * q * n * (n + 1) / 2.0;
  EXPECT_GE(std::sqrt(P(0, 0)), shortfall);
  EXPECT_LE(std::sqrt(P(0, 0)), shortfall + std::sqrt(n * sv * sv * dt * dt) + 1e-12);
  EXPECT_NEAR(P(2, 2), n * q, 1e-12);
  EXPECT_NEAR(P(1, 2), v * dt * q * n * (n - 1) / 2.0, 1e-10);
  EXPECT_NEAR(P(1, 1), v * v * dt * dt * q * (n - 1.0) * n * (2.0 * n - 1) / 6.0, 1e-9);
  EXPECT_NEAR(P(0, 1), 0.0, 1e-12);
  EXPECT_NEAR(ekf.mean().x(), v * n * dt, 1e-9);
}

// Standing, the wheels count nothing and are exact: the heading stays as known, and the position
// grows only by the frame's wander, the same in every direction (the UAV's odometry frame it is
// located in moves under it). Driving adds the wheels' noise on top.
TEST(UgvEkf, StandingStillOnlyTheFrameWandersAndTheHeadingStaysKnown) {
  UgvEkfConfig config = one_shot();
  config.calibration.estimate = false;
  config.frame_walk_m_per_sqrt_s = 0.005;
  UgvEkf ekf(config);
  const Mat3 start = Vec3(1e-4, 1e-4, 1e-4).asDiagonal();
  ASSERT_EQ(ekf.update({TimePoint{}, {Vec2(0, 0), 0.7}, start}), UgvEkf::Update::kInitialized);
  const int n = 3000;  // 60 s
  for (int k = 1; k <= n; ++k)
    ASSERT_TRUE(ekf.predict(TimePoint{k * kOdomPeriod}, 0.0, 0.0));
  const Mat3 P = ekf.covariance();
  const double walk = 0.005 * 0.005 * 60.0;
  EXPECT_NEAR(P(0, 0), 1e-4 + walk, 1e-12);
  EXPECT_NEAR(P(1, 1), 1e-4 + walk, 1e-12);
  EXPECT_NEAR(P(0, 1), 0.0, 1e-15);
  EXPECT_NEAR(P(2, 2), 1e-4, 1e-15);
  EXPECT_NEAR(ekf.mean().z(), 0.7, 1e-15);
  // One second of driving: the wheels' noise along the heading, beyond the frame's.
  for (int k = n + 1; k <= n + 50; ++k)
    ASSERT_TRUE(ekf.predict(TimePoint{k * kOdomPeriod}, 0.3, 0.0));
  const Vec2 along(std::cos(0.7), std::sin(0.7));
  const double grown = along.dot(ekf.covariance().topLeftCorner<2, 2>() * along) -
                       along.dot(P.topLeftCorner<2, 2>() * along);
  EXPECT_GT(grown, 0.005 * 0.005 * 1.0 + 0.5 * 0.0336 * 0.0336 * 50 * 0.02 * 0.02);
  EXPECT_GT(ekf.covariance()(2, 2), 1e-4 + 0.5 * 0.0292 * 0.0292 * 50 * 0.02 * 0.02);
}

// A robot that starts with its heading known to 0.3 rad only and drives 4 m blind ends up
// d (1 - cos e) short of where the filter thinks, for its true heading error e: never longer.
// The linearised covariance knows nothing of it (0.02 m along the path, from the wheels'
// noise); the filter's along-path standard deviation must cover its rms over e ~ N(0, 0.3^2),
// here 0.30 m.
TEST(UgvEkf, AnUncertainHeadingWidensTheCovarianceAlongThePath) {
  UgvEkf ekf(white_noise_config());
  const double sigma_yaw = 0.3;
  Mat3 r = Mat3::Identity() * 1e-6;
  r(2, 2) = sigma_yaw * sigma_yaw;
  ASSERT_EQ(ekf.update({TimePoint{}, {Vec2(0, 0), 0.0}, r}), UgvEkf::Update::kInitialized);
  const double v = 0.5, dt = 0.02;
  const int n = 400;  // 4 m
  for (int k = 1; k <= n; ++k)
    ASSERT_TRUE(ekf.predict(TimePoint{k * kOdomPeriod}, v, 0.0));
  const double d = v * dt * n;
  // E[(d (1 - cos e))^2] over the heading's Gaussian, by quadrature over +-6 sigma.
  double mean_sq = 0.0, weight = 0.0;
  for (int i = -600; i <= 600; ++i) {
    const double e = sigma_yaw * i / 100.0;
    const double w = std::exp(-0.5 * (i / 100.0) * (i / 100.0));
    mean_sq += w * std::pow(d * (1.0 - std::cos(e)), 2);
    weight += w;
  }
  const double rms_shortfall = std::sqrt(mean_sq / weight);
  EXPECT_NEAR(rms_shortfall, 0.30, 0.01);
  EXPECT_GE(std::sqrt(ekf.covariance()(0, 0)), rms_shortfall);
  // and not far beyond it (the wheels' own noise adds 0.02 m): room to drive stays.
  EXPECT_LE(std::sqrt(ekf.covariance()(0, 0)), 1.3 * rms_shortfall);
  // Across the path the linearisation holds: sigma_yaw d, as before.
  EXPECT_NEAR(std::sqrt(ekf.covariance()(1, 1)), sigma_yaw * d, 0.02);
}

TEST(UgvEkf, RejectsAMeasurementFarOutsideTheGateThenResetsIfItPersists) {
  UgvEkfConfig cfg = one_shot();
  cfg.reset_after_rejections = 5;
  UgvEkf ekf(cfg);
  ASSERT_EQ(ekf.update({TimePoint{}, {Vec2(0, 0), 0.0}, rpe_covariance()}),
            UgvEkf::Update::kInitialized);
  const PoseMeasurement far{TimePoint{}, {Vec2(5.0, 0.0), 0.0}, rpe_covariance()};
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(ekf.update(far), UgvEkf::Update::kRejectedGate);
  EXPECT_NEAR(ekf.mean().x(), 0.0, 1e-12);  // untouched
  EXPECT_EQ(ekf.counters().rejected_gate, 4u);
  // The fifth in a row: the filter must have diverged; it restarts from the measurement.
  EXPECT_EQ(ekf.update(far), UgvEkf::Update::kReset);
  EXPECT_NEAR(ekf.mean().x(), 5.0, 1e-12);
  EXPECT_EQ(ekf.counters().resets, 1u);
  // A good measurement between outliers restarts the count.
  EXPECT_EQ(ekf.update({TimePoint{}, {Vec2(5.1, 0.0), 0.0}, rpe_covariance()}),
            UgvEkf::Update::kApplied);
}

TEST(UgvEkf, AMeasurementBeyondTheRobustBoundPullsLessThanOneInside) {
  // sigma 0.2 m on both sides: a measurement 0.9 m off has d2 = 10.1, inside the gate (16.27)
  // but beyond the robust bound (7.81). A plain update would move the estimate half way.
  const auto moved_by = [](double robust_chi2, double offset) {
    UgvEkfConfig cfg = white_noise_config();
    cfg.robust_chi2 = robust_chi2;
    UgvEkf ekf(cfg);
    EXPECT_EQ(ekf.update({TimePoint{}, {Vec2(0, 0), 0.0}, rpe_covariance()}),
              UgvEkf::Update::kInitialized);
    EXPECT_EQ(ekf.update({TimePoint{}, {Vec2(offset, 0), 0.0}, rpe_covariance()}),
              UgvEkf::Update::kApplied);
    return ekf.mean().x();
  };
  EXPECT_NEAR(moved_by(16.27, 0.9), 0.45, 1e-9);
  EXPECT_LT(moved_by(7.81, 0.9), 0.43);
  EXPECT_NEAR(moved_by(7.81, 0.5), 0.25, 1e-9);  // inside the bound: a plain update
}

TEST(UgvEkf, AngleWrapAcrossPlusMinusPi) {
  UgvEkf ekf(one_shot());
  ASSERT_EQ(ekf.update({TimePoint{}, {Vec2(0, 0), 3.10}, rpe_covariance()}),
            UgvEkf::Update::kInitialized);
  // -3.10 is 0.083 rad away across the wrap, not 6.2 rad.
  ASSERT_EQ(ekf.update({TimePoint{}, {Vec2(0, 0), -3.10}, rpe_covariance()}),
            UgvEkf::Update::kApplied);
  const double yaw = ekf.mean().z();
  EXPECT_GE(yaw, -M_PI);
  EXPECT_LT(yaw, M_PI);
  EXPECT_NEAR(std::abs(yaw), M_PI, 0.05);  // half way, across the wrap
  EXPECT_NEAR(std::cos(yaw), -1.0, 1e-3);
  // Predicting through the wrap keeps the angle in range.
  for (int k = 1; k <= 50; ++k)
    ASSERT_TRUE(ekf.predict(TimePoint{k * kOdomPeriod}, 0.0, 0.5));
  EXPECT_GE(ekf.mean().z(), -M_PI);
  EXPECT_LT(ekf.mean().z(), M_PI);
}

TEST(UgvEkf, ALateMeasurementGivesTheSameStateAsOneInTime) {
  Rng rng(4);
  std::vector<std::pair<double, double>> odo;
  odo.reserve(60);
  for (int k = 0; k < 60; ++k)
    odo.emplace_back(0.5 + rng.gaussian(0, 0.03), 0.1 + rng.gaussian(0, 0.03));
  const PoseMeasurement init{TimePoint{}, {Vec2(0, 0), 0.0}, rpe_covariance()};
  const PoseMeasurement z{TimePoint{20 * kOdomPeriod}, {Vec2(0.3, 0.1), 0.08}, rpe_covariance()};

  UgvEkf in_time(one_shot()), late(one_shot());
  in_time.update(init);
  late.update(init);
  for (int k = 1; k <= 60; ++k) {
    const TimePoint t{k * kOdomPeriod};
    ASSERT_TRUE(in_time.predict(t, odo[k - 1].first, odo[k - 1].second));
    ASSERT_TRUE(late.predict(t, odo[k - 1].first, odo[k - 1].second));
    if (k == 20) {
      ASSERT_EQ(in_time.update(z), UgvEkf::Update::kApplied);
    }
  }
  ASSERT_EQ(late.update(z), UgvEkf::Update::kApplied);  // 0.8 s late
  EXPECT_LT((late.mean() - in_time.mean()).norm(), 1e-9);
  EXPECT_LT((late.covariance() - in_time.covariance()).norm(), 1e-12);
}

TEST(UgvEkf, RejectsInvalidStaleAndOutOfOrderInput) {
  UgvEkf ekf(one_shot());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ekf.update({TimePoint{}, {Vec2(nan, 0), 0.0}, rpe_covariance()}),
            UgvEkf::Update::kRejectedInvalid);
  EXPECT_EQ(ekf.update({TimePoint{}, {Vec2(0, 0), 0.0}, Mat3::Zero()}),
            UgvEkf::Update::kRejectedInvalid);
  EXPECT_FALSE(ekf.initialized());
  ASSERT_EQ(ekf.update({TimePoint{}, {Vec2(0, 0), 0.0}, rpe_covariance()}),
            UgvEkf::Update::kInitialized);
  for (int k = 1; k <= 200; ++k)
    ASSERT_TRUE(ekf.predict(TimePoint{k * kOdomPeriod}, 0.1, 0.0));
  // Older than the odometry history (1.28 s): cannot be placed.
  EXPECT_EQ(ekf.update({TimePoint{1s}, {Vec2(0.1, 0), 0.0}, rpe_covariance()}),
            UgvEkf::Update::kRejectedStale);
  EXPECT_EQ(ekf.predict(TimePoint{100 * kOdomPeriod}, 0.1, 0.0).code(), Errc::kOutOfRange);
  EXPECT_EQ(ekf.predict(TimePoint{300 * kOdomPeriod}, nan, 0.0).code(), Errc::kInvalidArgument);
  EXPECT_EQ(ekf.counters().rejected_stale, 1u);
  EXPECT_EQ(ekf.counters().rejected_invalid, 2u);
  EXPECT_EQ(ekf.counters().rejected_odometry, 2u);
}

TEST(UgvEkf, InitialisesAtTheMeasurementTimeAndCatchesUpWithOdometry) {
  UgvEkf ekf(one_shot());
  for (int k = 1; k <= 50; ++k)
    ASSERT_TRUE(ekf.predict(TimePoint{k * kOdomPeriod}, 0.5, 0.0));
  EXPECT_FALSE(ekf.initialized());
  // An RPE of the pose at 0.6 s arrives at 1.0 s: the 0.4 s of driving since then count.
  ASSERT_EQ(ekf.update({TimePoint{30 * kOdomPeriod}, {Vec2(3.0, 1.0), 0.0}, rpe_covariance()}),
            UgvEkf::Update::kInitialized);
  EXPECT_NEAR(ekf.mean().x(), 3.0 + 0.5 * 0.4, 1e-9);
  EXPECT_EQ(ekf.stamp(), TimePoint{50 * kOdomPeriod});
}

// After a gap the state cannot tell an outlier from a fix (here it knows its position to 1 m):
// the first relative pose waits for the next to agree with it. A tag a metre off is dropped;
// two that agree are both applied; soon after, each is applied on its own again.
TEST(UgvEkf, AfterAGapARelativePoseWaitsForTheNextToConfirmIt) {
  for (const double reacquire : {3.0, 0.0}) {
    UgvEkfConfig cfg = white_noise_config();
    cfg.reacquire_after_s = reacquire;
    UgvEkf ekf(cfg);
    TimePoint t{};
    ASSERT_TRUE(ekf.predict(t, 0.0, 0.0));
    const Mat3 unsure = Vec3(1.0, 1.0, 0.3 * 0.3).asDiagonal();
    ASSERT_EQ(ekf.update({t, {Vec2(0.0, 0.0), 0.0}, unsure}), UgvEkf::Update::kInitialized);
    const auto stand = [&](Duration d) { stand_still(ekf, t, d); };
    stand(4s);  // nothing applied for 4 s; the robot is truly at (0.1, 0), heading 0
    const PoseMeasurement outlier{t, {Vec2(1.1, 0.6), 0.3}, rpe_covariance()};
    const UgvEkf::Update first = ekf.update(outlier);
    if (reacquire == 0.0) {
      // Inside a gate that wide, it is taken: the estimate jumps towards it.
      EXPECT_EQ(first, UgvEkf::Update::kApplied);
      EXPECT_GT(ekf.pose().p.x(), 0.8);
      continue;
    }
    EXPECT_EQ(first, UgvEkf::Update::kHeld);
    EXPECT_NEAR(ekf.pose().p.x(), 0.0, 1e-9);  // untouched while held
    stand(100ms);
    EXPECT_EQ(ekf.update({t, {Vec2(0.12, -0.02), 0.01}, rpe_covariance()}),
              UgvEkf::Update::kHeld);  // disagrees with the outlier: the outlier is dropped
    EXPECT_EQ(ekf.counters().unconfirmed, 1u);
    EXPECT_NEAR(ekf.pose().p.x(), 0.0, 1e-9);
    stand(100ms);
    EXPECT_EQ(ekf.update({t, {Vec2(0.08, 0.01), -0.01}, rpe_covariance()}),
              UgvEkf::Update::kApplied);  // agrees: both applied
    EXPECT_EQ(ekf.counters().updates, 2u);
    EXPECT_NEAR(ekf.pose().p.x(), 0.1, 0.05);
    EXPECT_NEAR(ekf.pose().p.y(), 0.0, 0.05);
    stand(500ms);
    EXPECT_EQ(ekf.update({t, {Vec2(0.1, 0.0), 0.0}, rpe_covariance()}), UgvEkf::Update::kApplied);
    EXPECT_EQ(ekf.counters().held, 2u);
  }
}

// The start: nothing checks the first relative pose, so it waits for one that agrees with it.
// An outlier first is dropped when the next disagrees; the next pair that agrees starts the
// estimator (both applied). One older than the window confirms nothing. Window 0: the first
// starts it alone.
TEST(UgvEkf, StartsFromTwoRelativePosesThatAgree) {
  for (const double window : {2.0, 0.0}) {
    UgvEkfConfig cfg = white_noise_config();
    cfg.start_window_s = window;
    UgvEkf ekf(cfg);
    TimePoint t{};
    const auto stand = [&](Duration d) { stand_still(ekf, t, d); };
    stand(100ms);  // the robot stands at (0, 0), heading 0
    const UgvEkf::Update first = ekf.update({t, {Vec2(1.5, 1.0), 0.3}, rpe_covariance()});
    if (window == 0.0) {
      EXPECT_EQ(first, UgvEkf::Update::kInitialized);  // on the outlier
      EXPECT_GT(ekf.pose().p.x(), 1.4);
      continue;
    }
    EXPECT_EQ(first, UgvEkf::Update::kHeld);
    EXPECT_FALSE(ekf.initialized());
    stand(100ms);
    EXPECT_EQ(ekf.update({t, {Vec2(0.02, -0.01), 0.01}, rpe_covariance()}),
              UgvEkf::Update::kHeld);  // unlike the outlier: the outlier is dropped
    EXPECT_EQ(ekf.counters().unconfirmed, 1u);
    EXPECT_FALSE(ekf.initialized());
    stand(2500ms);  // too late to confirm the one before
    EXPECT_EQ(ekf.update({t, {Vec2(-0.02, 0.01), -0.01}, rpe_covariance()}), UgvEkf::Update::kHeld);
    EXPECT_EQ(ekf.counters().unconfirmed, 2u);
    stand(100ms);
    EXPECT_EQ(ekf.update({t, {Vec2(0.01, 0.02), 0.0}, rpe_covariance()}),
              UgvEkf::Update::kInitialized);  // agrees: both applied
    EXPECT_EQ(ekf.counters().updates, 1u);    // the first starts it, the second is fused
    EXPECT_NEAR(ekf.pose().p.x(), 0.0, 0.03);
    EXPECT_NEAR(ekf.pose().p.y(), 0.015, 0.03);
    EXPECT_LT(ekf.covariance()(0, 0), rpe_covariance()(0, 0));
  }
}
