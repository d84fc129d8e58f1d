// Lifelike metrics of a motion against a reference capture: what a viewer notices in a body that
// plays pieces of a recording — knees bent more often than the speaker's, jerky joints, a body
// that never rests or rests too long, feet that slide. Each is a ratio to the reference's own
// value (1 = as the capture), computed in two steps so a reference of several clips is read once:
// lifelike_facts per motion, lifelike_reference over the reference's clips, lifelike_motion.
// The path metrics (junctions, plays, back-jumps) are in played_paths.h.
//
// Positions are frames x (3 * joints) in centimetres (evaluate.h length_unit_to_cm), Y up,
// joint 0 the root. "Root-relative" is every joint minus the root in the same frame.
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "engine/motion/motion.h"

namespace gmg {

struct LifelikeParams {
  double knee_percentile = 90.0;     // the reference's knee bend above which a frame counts as deeply bent
  double jerk_percentile = 99.0;     // of the per-frame largest jerk: how bad the worst moments are
  double still_percentile = 5.0;     // the reference's speed under which a frame is still
  double foot_low_percentile = 5.0;  // a foot's low height: this percentile of its own height
  double foot_height_cm = 3.0;       // a foot this close to its low height stands on the floor
  double foot_speed_cm_s = 10.0;     // ... and slides when it moves faster than this horizontally
  double back_jump_window_s = 10.0;  // a piece starting at a frame played this recently jumps back
};

// Throws gmg::Error naming the parameter and its range: percentiles in (0, 100), the rest > 0.
void check_lifelike_params(const LifelikeParams& params);

// The joints the metrics look at, found by name and hierarchy.
struct KneeJoint {
  int parent = -1, knee = -1, child = -1;  // child: the knee's child with the largest subtree
};
struct LifelikeJoints {
  // Knees: names holding "knee", or ending in "leg" but not "upleg" (case-insensitive: ZEGGS
  // RightLeg, GENEA b_r_leg, SMPL-X left_knee), with a parent and a child.
  std::vector<KneeJoint> knees;
  // Body joints: every joint but the root, fingers (thumb, index, middle, ring, pinky, finger),
  // eyes, jaw and leaves (joints without child joints: end and tip joints).
  std::vector<int> body;
  // Feet: names holding "ankle" or "foot" but not "toe" or "end".
  std::vector<int> feet;
};
LifelikeJoints lifelike_joints(const Skeleton& skeleton);

// 180 degrees minus the angle at `joint` between its parent bone and its child bone: 0 when
// parent, joint and child are in a straight line, 90 at a right angle. 0 for a bone of length 0.
double bend_angle_deg(const Eigen::Vector3d& parent, const Eigen::Vector3d& joint, const Eigen::Vector3d& child);

// The longest run of consecutive values strictly below `threshold` (a count of values).
int longest_run_below(const std::vector<double>& values, double threshold);

// What one motion contributes, frame by frame.
struct LifelikeFacts {
  double fps = 0.0;
  // Per frame t = 0..T-1: the larger knee bend (degrees); empty without knees.
  std::vector<double> knee_bend_deg;
  // |p(t+3) - 3 p(t+2) + 3 p(t+1) - p(t)| * fps^3 of the root-relative body joints (cm/s^3):
  // their sum and count over t = 0..T-4 and the body joints, and per t the largest.
  double jerk_sum = 0.0;
  long jerk_count = 0;
  std::vector<double> jerk_frame_max;
  // Per t = 1..T-1: the largest root-relative body-joint speed |p(t) - p(t-1)| * fps (cm/s).
  std::vector<double> speed_frame_max;
  // Frames t = 1..T-1 in which some foot is within foot_height_cm above its low height and moves
  // faster than foot_speed_cm_s horizontally (x, z) from t-1 to t; over frames t = 1..T-1.
  long slide_frames = 0, slide_of = 0;
  bool has_feet = false;
};
LifelikeFacts lifelike_facts(const Eigen::MatrixXd& pos, double fps, const LifelikeJoints& joints,
                             const LifelikeParams& params);

// The reference's values, its clips pooled (frames of all clips together; a still run within one
// clip, each foot's low height from its own clip).
struct LifelikeReference {
  double fps = 0.0;
  // Field names say the default percentiles (LifelikeParams).
  double knee_p90_deg = std::numeric_limits<double>::quiet_NaN();  // knee_percentile of the knee bend
  double jerk_mean = 0.0;                                          // cm/s^3
  double jerk_p99 = 0.0;                                           // jerk_percentile of the per-frame largest jerk
  double still_speed_cm_s = 0.0;                                   // still_percentile of the per-frame largest speed
  int still_longest_frames = 0;
  double foot_slide_share = std::numeric_limits<double>::quiet_NaN();  // NaN without feet
};
// Throws gmg::Error when the clips together have fewer than 4 frames of jerk.
LifelikeReference lifelike_reference(const std::vector<LifelikeFacts>& clips, const LifelikeParams& params);

// The scores; NaN where a metric is undefined (no knees or feet, a reference value of 0).
struct LifelikeMotion {
  static constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();
  // Share of frames whose knee bend exceeds the reference's knee_p90_deg (by more than 1e-6
  // degrees: rounding at a tie does not count; likewise a still frame is 1e-6 cm/s below), over
  // (100 - knee_percentile) / 100, the reference's own share: 1 = bent as often as the speaker.
  // Field names say the default percentiles (LifelikeParams).
  double knee_share_ratio = kUndefined;
  double knee_p90_deg = kUndefined, reference_knee_p90_deg = kUndefined;
  double body_jerk_ratio = kUndefined;      // mean jerk over the reference's
  double body_jerk_p99_ratio = kUndefined;  // jerk_percentile of the per-frame largest jerk over the reference's
  // Longest run of frames whose largest speed is below the reference's still_speed_cm_s, over the
  // reference's own longest such run; both in seconds too.
  double still_longest_ratio = kUndefined;
  double still_longest_s = kUndefined, reference_still_longest_s = kUndefined;
  double foot_slide_ratio = kUndefined;  // foot slide share over the reference's
  double foot_slide_share = kUndefined, reference_foot_slide_share = kUndefined;
};
LifelikeMotion lifelike_motion(const LifelikeFacts& motion, const LifelikeReference& reference,
                               const LifelikeParams& params);

}  // namespace gmg
