// Objective metrics: expected values are derived analytically here, never from the code under test.
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/metrics/metrics.h"

namespace gmg {
namespace {

constexpr double kPi = 3.14159265358979323846;
using PointFn = std::function<Eigen::Vector3d(int frame, int joint)>;

Eigen::MatrixXd make_motion(int frames, int joints, const PointFn& f) {
  Eigen::MatrixXd m(frames, 3 * joints);
  for (int t = 0; t < frames; ++t)
    for (int j = 0; j < joints; ++j) m.block<1, 3>(t, 3 * Eigen::Index{j}) = f(t, j).transpose();
  return m;
}

// A gesture-like motion: per-joint sums of sinusoids, deterministic per seed.
Eigen::MatrixXd wavy_motion(int frames, int joints, unsigned seed, double fps = 30.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.2, 3.0);
  std::vector<double> c(static_cast<std::size_t>(joints * 9));
  for (double& x : c) x = u(rng);
  return make_motion(frames, joints, [&](int f, int j) {
    const double t = f / fps;
    const double* k = &c[static_cast<std::size_t>(9 * j)];
    return Eigen::Vector3d(k[0] * 10 * std::sin(k[1] * t + k[2]), k[3] * 10 * std::sin(k[4] * t + k[5]),
                           k[6] * 10 * std::cos(k[7] * t + k[8]));
  });
}

template <typename F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "<no gmg::Error thrown>";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(Metrics, MotionAgainstItselfHasZeroSynAndHellinger) {
  const Eigen::MatrixXd m = wavy_motion(200, 4, 1);
  EXPECT_EQ(metric_syn(m, m, 30.0), 0.0);
  EXPECT_EQ(metric_hellinger_speed(m, m, 30.0, {}, MetricParams{}), 0.0);
  // Sanity that the motion is not trivially static, so the zeros above mean something.
  EXPECT_GT(metric_syn(m, wavy_motion(200, 4, 2), 30.0), 1.0);
}

TEST(Metrics, SynIsTheMeanSpeedDifference) {
  // Truth moves at 2 units/s along x, generated at 5 units/s along y: directions do not matter.
  const double fps = 25.0;
  const Eigen::MatrixXd truth = make_motion(50, 2, [&](int f, int) { return Eigen::Vector3d(2.0 * f / fps, 0, 0); });
  const Eigen::MatrixXd gen = make_motion(50, 2, [&](int f, int) { return Eigen::Vector3d(0, 5.0 * f / fps, 0); });
  EXPECT_NEAR(metric_syn(gen, truth, fps), 3.0, 1e-9);
  EXPECT_NEAR(metric_syn(truth, gen, fps), 3.0, 1e-9);
}

TEST(Metrics, ConstantVelocityHasZeroJerkAndAcceleration) {
  // Dyadic steps keep every position exact, so any non-zero result is a formula error.
  const Eigen::MatrixXd m =
      make_motion(40, 3, [](int f, int j) { return Eigen::Vector3d(0.25 * f + j, -0.125 * f, 0.5 * j * f + 3.0); });
  EXPECT_NEAR(metric_jerk(m, 30.0), 0.0, 1e-9);
  EXPECT_NEAR(metric_acceleration(m, 30.0), 0.0, 1e-9);
  // And a non-linear motion is not 0 (guards against a metric that always returns 0).
  EXPECT_GT(metric_acceleration(wavy_motion(40, 3, 5), 30.0), 1.0);
}

TEST(Metrics, CubicMotionMatchesAnalyticJerkAndAcceleration) {
  // Joint 0: x = a0 t^3 + b0 t^2; joint 1: z = a1 t^3 + b1 t^2 (its acceleration changes sign).
  // Third difference of a cubic = 6 a dt^3 exactly -> jerk 6|a|. Second difference over frames
  // f, f+1, f+2 = (6 a t_c + 2 b) dt^2 exactly, t_c = (f + 1) / fps.
  const double fps = 30.0, a0 = 2.0, b0 = 3.0, a1 = -1.5, b1 = 0.5;
  const int frames = 61;
  const Eigen::MatrixXd m = make_motion(frames, 2, [&](int f, int j) {
    const double t = f / fps;
    if (j == 0) return Eigen::Vector3d(a0 * t * t * t + b0 * t * t, 1.0, 0.0);
    return Eigen::Vector3d(0.0, -2.0, a1 * t * t * t + b1 * t * t);
  });
  EXPECT_NEAR(metric_jerk(m, fps), (6 * std::abs(a0) + 6 * std::abs(a1)) / 2, 1e-6);

  double expected_acc = 0.0;
  for (int f = 0; f + 2 < frames; ++f) {
    const double tc = (f + 1) / fps;
    expected_acc += std::abs(6 * a0 * tc + 2 * b0) + std::abs(6 * a1 * tc + 2 * b1);
  }
  expected_acc /= 2.0 * (frames - 2);
  EXPECT_NEAR(metric_acceleration(m, fps), expected_acc, 1e-6);
  // Closed form for joint 0 alone (all its terms are positive): 6 a (T-1) / (2 fps) + 2 b.
  const Eigen::MatrixXd j0 = m.leftCols(3);
  EXPECT_NEAR(metric_acceleration(j0, fps), 6 * a0 * (frames - 1) / (2 * fps) + 2 * b0, 1e-6);
}

TEST(Metrics, DivOfStraightLineIsZero) {
  // One joint moves diagonally at constant velocity; another only jitters by 1e-7 units, below
  // the near-stationary cut, so its random directions must not count.
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1e-7);
  const Eigen::MatrixXd m = make_motion(100, 2, [&](int f, int j) {
    if (j == 0) return Eigen::Vector3d(0.3 * f, -0.2 * f, 0.1 * f);
    return Eigen::Vector3d(noise(rng), 5.0 + noise(rng), noise(rng));
  });
  EXPECT_EQ(metric_div(m, 30.0, MetricParams{}), 0.0);
}

TEST(Metrics, DivCountsDirectionChanges) {
  const MetricParams params;
  // Zig-zag: the sideways component flips every frame (a 157 degree turn each frame).
  const Eigen::MatrixXd zigzag = make_motion(100, 1, [](int f, int) { return Eigen::Vector3d(f, 5.0 * (f % 2), 0); });
  EXPECT_DOUBLE_EQ(metric_div(zigzag, 30.0, params), 1.0);

  // Staircase: velocity +x, +x, +y, +y, ...: a 90 degree turn at every other frame.
  Eigen::Vector3d p(0, 0, 0);
  std::vector<Eigen::Vector3d> stairs{p};
  for (int k = 1; k < 201; ++k) {
    p += ((k - 1) / 2 % 2 == 0) ? Eigen::Vector3d(1, 0, 0) : Eigen::Vector3d(0, 1, 0);
    stairs.push_back(p);
  }
  const Eigen::MatrixXd staircase =
      make_motion(201, 1, [&](int f, int) { return stairs[static_cast<std::size_t>(f)]; });
  EXPECT_NEAR(metric_div(staircase, 30.0, params), 0.5, 0.01);

  // A circle sampled at 60 frames per turn turns 6 degrees a frame: smooth, never "large".
  const Eigen::MatrixXd circle = make_motion(150, 1, [](int f, int) {
    return Eigen::Vector3d(10 * std::cos(2 * kPi * f / 60), 10 * std::sin(2 * kPi * f / 60), 0);
  });
  EXPECT_EQ(metric_div(circle, 30.0, params), 0.0);

  // A hexagon traversed one side per frame turns 60 degrees every frame: above 45, below 90.
  const Eigen::MatrixXd hexagon = make_motion(
      60, 1, [](int f, int) { return Eigen::Vector3d(std::cos(2 * kPi * f / 6), std::sin(2 * kPi * f / 6), 0); });
  EXPECT_DOUBLE_EQ(metric_div(hexagon, 30.0, params), 1.0);
  MetricParams wide = params;
  wide.div_angle_deg = 90.0;
  EXPECT_EQ(metric_div(hexagon, 30.0, wide), 0.0);
}

// Mean joint speed proportional to |sin(pi (t - phase) / period)|: minima at phase + k period.
Eigen::MatrixXd beat_motion(double fps, double period, double phase, int frames) {
  return make_motion(frames, 2, [&](int f, int j) {
    const double c = std::cos(kPi * (f / fps - phase) / period);
    return j == 0 ? Eigen::Vector3d(20 * c, 0, 1) : Eigen::Vector3d(0, 0, 40 * c);
  });
}

TEST(Metrics, MotionBeatsAreSpeedMinima) {
  const double fps = 30.0;
  const MetricParams params;
  const std::vector<double> beats = motion_beats(beat_motion(fps, 1.0, 0.0, 181), fps, params);
  ASSERT_EQ(beats.size(), 5u);  // 1..5 s; the ends (0 s, 6 s) are never minima
  for (std::size_t k = 0; k < beats.size(); ++k) EXPECT_NEAR(beats[k], k + 1.0, 1e-9);

  // Minima half a frame after frame times: sub-frame refinement places them there.
  const double half = 0.5 / fps;
  const std::vector<double> shifted = motion_beats(beat_motion(fps, 1.0, half, 181), fps, params);
  ASSERT_EQ(shifted.size(), 5u);
  for (std::size_t k = 0; k < shifted.size(); ++k) EXPECT_NEAR(shifted[k], k + 1.0 + half, 0.01 / fps);

  // A held pose: one beat in the middle of the still run.
  const Eigen::MatrixXd hold = make_motion(61, 1, [](int f, int) {
    const int g = f < 20 ? f : (f < 40 ? 20 : f - 20);
    return Eigen::Vector3d(g, 0, 0);
  });
  MetricParams raw = params;
  raw.smooth_window = 0;
  const std::vector<double> held = motion_beats(hold, fps, raw);
  ASSERT_EQ(held.size(), 1u);
  EXPECT_NEAR(held[0], 30.0 / fps, 1e-12);

  EXPECT_TRUE(
      motion_beats(make_motion(30, 2, [](int, int j) { return Eigen::Vector3d(j, 1, 2); }), fps, params).empty());
}

TEST(Metrics, BeatConsistencyFallsAsAudioBeatsShift) {
  const double fps = 30.0;
  const MetricParams params;
  const Eigen::MatrixXd m = beat_motion(fps, 1.0, 0.0, 181);
  auto bc_shifted = [&](double shift) {
    std::vector<double> audio;
    for (int k = 1; k <= 5; ++k) audio.push_back(k + shift);
    return metric_bc(m, fps, audio, params);
  };
  const double bc0 = bc_shifted(0.0), bc1 = bc_shifted(0.05), bc2 = bc_shifted(0.1), bc3 = bc_shifted(0.2);
  EXPECT_GT(bc0, 0.999);
  EXPECT_LT(bc1, bc0);
  EXPECT_LT(bc2, bc1);
  EXPECT_LT(bc3, bc2);
  EXPECT_GT(bc3, 0.0);
  // With sigma = 0.05 s a shift of d gives exp(-d^2 / (2 * 0.05^2)).
  EXPECT_NEAR(bc1, std::exp(-0.5), 1e-6);
  EXPECT_NEAR(bc2, std::exp(-2.0), 1e-6);
  // Early shifts count like late ones.
  EXPECT_NEAR(bc_shifted(-0.1), bc2, 1e-6);

  EXPECT_EQ(metric_bc(m, fps, {}, params), 0.0);
  const Eigen::MatrixXd still = make_motion(100, 1, [](int, int) { return Eigen::Vector3d(1, 2, 3); });
  EXPECT_EQ(metric_bc(still, fps, {1.0, 2.0}, params), 0.0);
}

TEST(Metrics, HellingerBounds) {
  const double fps = 30.0;
  const MetricParams params;  // 1 unit/s bins over [0, 50), plus overflow
  auto constant_speed = [&](double speed, int joints = 1) {
    return make_motion(60, joints, [&](int f, int j) { return Eigen::Vector3d(speed * f / fps, j, 0); });
  };
  // Disjoint supports: every speed of one in bin 5, of the other in bin 20.
  EXPECT_DOUBLE_EQ(metric_hellinger_speed(constant_speed(5.5), constant_speed(20.5), fps, {}, params), 1.0);
  // Speeds above the range land in the overflow bin instead of being dropped.
  EXPECT_DOUBLE_EQ(metric_hellinger_speed(constant_speed(1000), constant_speed(10.5), fps, {}, params), 1.0);
  EXPECT_EQ(metric_hellinger_speed(constant_speed(1000), constant_speed(80), fps, {}, params), 0.0);

  // Half of gen's mass where all of truth's is: H = sqrt(1 - sqrt(0.5)).
  const Eigen::MatrixXd half =
      make_motion(60, 2, [&](int f, int j) { return Eigen::Vector3d((j == 0 ? 5.5 : 20.5) * f / fps, j, 0); });
  EXPECT_NEAR(metric_hellinger_speed(half, constant_speed(5.5, 2), fps, {}, params), std::sqrt(1 - std::sqrt(0.5)),
              1e-12);
  // Joint selection: joint 0 matches, joint 1 does not.
  EXPECT_EQ(metric_hellinger_speed(half, constant_speed(5.5, 2), fps, {0}, params), 0.0);
  EXPECT_DOUBLE_EQ(metric_hellinger_speed(half, constant_speed(5.5, 2), fps, {1}, params), 1.0);

  // Random walks: within [0, 1] and symmetric.
  std::mt19937 rng(11);
  for (int trial = 0; trial < 10; ++trial) {
    std::normal_distribution<double> step(0.0, 0.2 + 0.1 * trial);
    auto walk = [&](int frames) {
      Eigen::MatrixXd m = Eigen::MatrixXd::Zero(frames, 9);
      for (int t = 1; t < frames; ++t)
        for (int c = 0; c < 9; ++c) m(t, c) = m(t - 1, c) + step(rng);
      return m;
    };
    const Eigen::MatrixXd a = walk(120), b = walk(90);  // frame counts may differ
    const double hab = metric_hellinger_speed(a, b, fps, {}, params);
    EXPECT_GE(hab, 0.0);
    EXPECT_LE(hab, 1.0);
    EXPECT_EQ(hab, metric_hellinger_speed(b, a, fps, {}, params));
  }
}

TEST(Metrics, ShapeMismatchNamesBothShapes) {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Zero(10, 6), b = Eigen::MatrixXd::Zero(12, 6);
  const Eigen::MatrixXd c = Eigen::MatrixXd::Zero(10, 9);
  const std::string frames = error_message([&] { metric_syn(a, b, 30.0); });
  EXPECT_TRUE(contains(frames, "10 frames") && contains(frames, "12 frames")) << frames;
  const std::string joints = error_message([&] { metric_syn(a, c, 30.0); });
  EXPECT_TRUE(contains(joints, "2 joints") && contains(joints, "3 joints")) << joints;
  const std::string hel = error_message([&] { metric_hellinger_speed(a, c, 30.0, {}, MetricParams{}); });
  EXPECT_TRUE(contains(hel, "2 joints") && contains(hel, "3 joints")) << hel;
}

TEST(Metrics, InvalidInputsThrow) {
  const MetricParams params;
  const Eigen::MatrixXd three = Eigen::MatrixXd::Zero(3, 6);
  const std::string few = error_message([&] { metric_jerk(three, 30.0); });
  EXPECT_TRUE(contains(few, "4 frames") && contains(few, "got 3")) << few;
  EXPECT_NO_THROW(metric_acceleration(three, 30.0));
  EXPECT_THROW(metric_acceleration(Eigen::MatrixXd::Zero(2, 3), 30.0), Error);
  EXPECT_THROW(metric_syn(Eigen::MatrixXd::Zero(1, 3), Eigen::MatrixXd::Zero(1, 3), 30.0), Error);

  Eigen::MatrixXd nan = Eigen::MatrixXd::Zero(10, 6);
  nan(4, 5) = std::nan("");
  const std::string nan_msg = error_message([&] { metric_div(nan, 30.0, params); });
  EXPECT_TRUE(contains(nan_msg, "frame 4") && contains(nan_msg, "joint 1")) << nan_msg;
  EXPECT_THROW(metric_syn(nan, Eigen::MatrixXd::Zero(10, 6), 30.0), Error);

  const std::string cols = error_message([&] { metric_jerk(Eigen::MatrixXd::Zero(10, 7), 30.0); });
  EXPECT_TRUE(contains(cols, "7 columns")) << cols;
  EXPECT_THROW(metric_jerk(Eigen::MatrixXd::Zero(10, 6), 0.0), Error);
  EXPECT_THROW(metric_bc(Eigen::MatrixXd::Zero(10, 6), 30.0, {std::nan("")}, params), Error);
  EXPECT_THROW(metric_hellinger_speed(three, three, 30.0, {2}, params), Error);
  MetricParams bad = params;
  bad.bc_sigma_s = 0.0;
  EXPECT_THROW(metric_bc(Eigen::MatrixXd::Zero(10, 6), 30.0, {1.0}, bad), Error);
}

}  // namespace
}  // namespace gmg
