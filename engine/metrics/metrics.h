// Objective gesture metrics on joint world positions (SPEC "Evaluation"; paper 5.2 Table 2:
// Syn, BC, Div; GENEA numerical evaluations: average jerk / acceleration, Hellinger distance
// between speed histograms).
//
// Input: `pos` is frames x (3 * joints), columns x, y, z per joint, in the file's length unit
// ("units": centimetres for GENEA/ZEGGS BVH, metres for BEAT2), as motion_forward_kinematics
// returns it; `fps` > 0. Times are in seconds, frame f is at time f / fps.
// Common notation: p(t, j) is joint j's position at frame t, T the frame count, J the joints,
// v(t, j) = (p(t, j) - p(t-1, j)) * fps the backward-difference velocity (units/s, t >= 1).
//
// Every function throws gmg::Error when: the column count is 0 or not a multiple of 3, a value
// is NaN/inf, fps is not finite and > 0, a parameter is out of range, or there are fewer frames
// than the metric needs (the message says how many it needs and how many it got).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "engine/core/enum_names.h"

namespace gmg {

// Binning of the speed histograms behind the Hellinger distance.
//  - Overflow (ours, the default): hist_bin_count bins of hist_bin_width from 0, plus one bin for
//    every faster speed, so both histograms keep all their mass (fast whips count).
//  - Genea: the GENEA numerical evaluations' bins, numpy's histogram over the edges
//    arange(0, 49 + w, w) (w = hist_bin_width; the last bin is closed on the right); faster speeds
//    are dropped before normalising. On BEAT2, 38-67 % of all joint speeds exceed 49 cm/s.
enum class HistogramBins : std::uint8_t { Overflow, Genea };
inline constexpr EnumName<HistogramBins> kHistogramBinsNames[] = {{HistogramBins::Overflow, "overflow"},
                                                                  {HistogramBins::Genea, "genea"}};

struct MetricParams {
  // Beat consistency Gaussian width (s). Bailando's BeatAlign score, which DanceFormer-style BC
  // follows, uses exp(-d^2 / (2 * 9)) with d in frames of 60 fps AIST++ data, i.e. sigma = 3
  // frames = 0.05 s; expressed in seconds here so it does not change with the clip's fps.
  double bc_sigma_s = 0.05;

  // Motion-beat detection smooths the mean-joint-speed curve with a centred moving average of
  // 2 * (smooth_window / 2) + 1 frames (odd; shrunk at the ends; 0 or 1 = no smoothing).
  // Bailando smooths with a Gaussian of sigma 5 frames at 60 fps; 5 frames (std 1.4 frames,
  // ~0.05 s at GENEA's 30 fps) removes the 1-2 frame capture jitter that would otherwise add
  // spurious minima (inflating BC) while keeping stroke-to-stroke minima (>= ~0.3 s apart).
  int smooth_window = 5;

  // Div counts a velocity turn larger than this angle between consecutive frames as a "large"
  // direction change. Smooth curved gesture paths turn by ~10 deg/frame at 30 fps (a hand on a
  // 10 cm radius at 50 cm/s); 45 deg only fires at abrupt changes: reversals, stroke onsets.
  double div_angle_deg = 45.0;
  // Div skips a (frame, joint) turn when either velocity's speed is below this fraction of the
  // clip's mean joint speed: near-stationary joints have noise-dominated directions (a random
  // 3D direction exceeds 45 deg with probability 0.85). Relative, so it holds in cm and in m.
  double div_min_speed_frac = 0.05;

  // Speed histogram for Hellinger: hist_bin_count bins of hist_bin_width (units/s) starting at
  // 0, plus one overflow bin for speeds >= hist_bin_count * hist_bin_width. The defaults are
  // the GENEA numerical evaluation's bins (1 cm/s wide over [0, 50) cm/s; Gesticulator also
  // uses 1 cm/s), which assume centimetre data: for metre data use 0.01. GENEA drops speeds
  // above the range; the overflow bin keeps that mass instead, so both histograms sum to 1.
  double hist_bin_width = 1.0;
  int hist_bin_count = 50;
  HistogramBins hist_bins = HistogramBins::Overflow;
};

// Syn (units/s): mean over frames t = 1..T-1 and joints j of | |v_gen(t,j)| - |v_true(t,j)| |.
// Needs equal shapes (else gmg::Error naming both) and T >= 2. 0 for identical motions.
double metric_syn(const Eigen::MatrixXd& gen, const Eigen::MatrixXd& truth, double fps);

// Motion beats (s, ascending): local minima of the mean joint speed
//   s(t) = mean_j |p(t+1, j) - p(t-1, j)| * fps / 2      (central difference, t = 1..T-2,
// centred on frame t so a beat is not biased by half a frame), smoothed (smooth_window). A
// minimum is a sample (or a run of equal samples, e.g. a held pose, taken at its centre)
// strictly lower than its neighbours on both sides; the curve's ends are never minima. A single
// sample minimum is refined to sub-frame time by a parabola through it and its neighbours
// (offset clamped to +-0.5 frame). Needs T >= 3; a static motion has no beats.
std::vector<double> motion_beats(const Eigen::MatrixXd& pos, double fps, const MetricParams& params);

// BC (unitless, [0, 1]): mean over audio beats b of exp(-d_b^2 / (2 sigma^2)), d_b (s) the
// distance from b to the nearest motion beat (motion_beats), sigma = bc_sigma_s. Averaged over
// audio beats as Bailando's BeatAlign score does. Every audio beat counts, also ones outside the
// motion's span. No motion beats: every term is exp(-inf) = 0, so BC = 0. No audio beats: 0 too
// (nothing was matched; as in the Bailando-derived implementations that guard this case), which
// keeps the value finite for silent clips. Audio beats must be finite.
double metric_bc(const Eigen::MatrixXd& pos, double fps, const std::vector<double>& audio_beats_s,
                 const MetricParams& params);

// Div (unitless, [0, 1]): share of the (frame, joint) pairs, t = 1..T-2, in which the direction
// of joint j's velocity turns by more than div_angle_deg from v(t, j) to v(t+1, j). Per joint,
// not on the stacked 3J-vector, so a turn is a geometric turn of one joint's path (a stacked
// angle mixes independent joints and shrinks when other joints move fast). Pairs where
// |v(t,j)| or |v(t+1,j)| is below div_min_speed_frac * (mean of |v| over all t, j), or below
// 1e-12 units/s, are skipped. Straight constant-direction motion: 0; a direction flip every
// frame: 1. No pair left (e.g. a static motion): 0. Needs T >= 3.
double metric_div(const Eigen::MatrixXd& pos, double fps, const MetricParams& params);

// Average jerk (units/s^3): mean over t = 0..T-4 and joints of
//   |p(t+3) - 3 p(t+2) + 3 p(t+1) - p(t)| * fps^3.                      Needs T >= 4.
double metric_jerk(const Eigen::MatrixXd& pos, double fps);
// Average acceleration (units/s^2): mean over t = 0..T-3 and joints of
//   |p(t+2) - 2 p(t+1) + p(t)| * fps^2.                                  Needs T >= 3.
double metric_acceleration(const Eigen::MatrixXd& pos, double fps);

// Hellinger distance (unitless, [0, 1]) between the normalised speed histograms p (gen) and q
// (binned as params.hist_bins says; with Genea bins, a histogram left empty because every speed
// is faster than the range counts as maximally distant from a non-empty one: H = 1; both empty: 0)
// (truth): H = sqrt(1 - sum_i sqrt(p_i q_i)). Each histogram pools |v(t, j)| over t = 1..T-1
// and the given joints (all when `joints` is empty), as GENEA's "Total" histogram sums the
// per-joint ones; both use the same bins (MetricParams). Evaluated in the equal form (for
// normalised histograms) sqrt(sum_i (sqrt p_i - sqrt q_i)^2 / 2), exactly 0 for identical
// inputs. Needs equal joint counts (else gmg::Error naming both shapes) and T >= 2 in each; the
// frame counts may differ, since normalised histograms compare distributions. Joint indices
// must be in range.
double metric_hellinger_speed(const Eigen::MatrixXd& gen, const Eigen::MatrixXd& truth, double fps,
                              const std::vector<int>& joints, const MetricParams& params);

}  // namespace gmg
