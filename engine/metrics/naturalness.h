// Naturalness of generated motion against a reference (the truth, or the reference capture):
// is it as smooth as the capture, does it jump, does the root glide, how often does it cut.
//
// Positions are frames x (3 * joints) in centimetres, as elsewhere in engine/metrics; joint 0 is
// the root. "Root-relative" means every joint minus the root joint in the same frame, so root
// translation (where the speaker stands) does not count as gesture.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace gmg {

// Every joint minus joint 0, per frame (joint 0's own columns become 0).
Eigen::MatrixXd root_relative(const Eigen::MatrixXd& pos);

// Per-frame step: for t = 1..T-1, the largest root-relative joint displacement from frame t-1 to
// t (cm). T-1 values; a motion of fewer than 2 frames has none.
std::vector<double> frame_steps(const Eigen::MatrixXd& pos);

// The p-th percentile (0..100) of values with numpy's default (linear) interpolation. Values
// must not be empty.
double percentile(std::vector<double> values, double p);

// Mean root speed over t = 1..T-1: |root(t) - root(t-1)| * fps (cm/s).
double root_speed(const Eigen::MatrixXd& pos, double fps);

// What a reference clip contributes to the ratios, computed once and shared by every motion
// scored against it.
struct NaturalnessReference {
  double jerk = 0;          // root-relative average jerk (cm/s^3), metric_jerk's formula
  double acceleration = 0;  // root-relative average acceleration (cm/s^2)
  double root_speed = 0;    // cm/s
  double step_p999 = 0;     // 99.9th percentile of its frame_steps (cm)
};
NaturalnessReference naturalness_reference(const Eigen::MatrixXd& pos, double fps);

struct Naturalness {
  double jerk_ratio = 0;        // root-relative jerk / the reference's (1 = as smooth)
  double acc_ratio = 0;         // root-relative acceleration / the reference's
  double root_speed_ratio = 0;  // root speed / the reference's (0 when the reference's root is still)
  double jump_ratio = 0;        // largest frame step / the reference's 99.9th percentile step
  double step_share = 0;        // share of frame steps above the reference's 99.9th percentile
};

// Scores `pos` against a reference. Needs >= 4 frames (jerk); gmg::Error otherwise.
Naturalness naturalness(const Eigen::MatrixXd& pos, double fps, const NaturalnessReference& reference);

// Source-time discontinuities of a sequence of source frames (the graph frames the output was read
// from, in output order, before resampling): places where the next frame is not the previous
// one's natural successor (f + 1). Junctions that did not continue and unnatural edges inside a
// path both count; a repeated frame (a held pose) counts too.
int source_transitions(const std::vector<int>& source_frames);

// transitions / duration_s (0 for a non-positive duration).
double transitions_per_second(int transitions, double duration_s);

}  // namespace gmg
