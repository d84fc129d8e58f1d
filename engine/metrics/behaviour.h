// What a viewer notices beyond smoothness: sliding feet, a figure that never rests, a stretch of
// the reference played again and again, and seeds that give the same motion.
//
// Positions are frames x (3 * joints) in centimetres (engine/metrics/evaluate.h
// length_unit_to_cm), Y up, joint 0 the root.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "engine/motion/body_parts.h"

namespace gmg {

// Foot sliding: the share of frames t >= 1 in which some ankle near the floor moves along it faster
// than speed_cm_s (horizontal speed, world space: a foot lifting off or setting down moves
// vertically near the floor without sliding). Near the floor: within height_cm of that ankle's
// floor, its 1st-percentile height over the motion. A planted foot of the capture moves at a few
// cm/s (capture noise); a foot carried along by a transition or a gliding root moves faster. 0
// without legs or with fewer than 2 frames.
struct FootSlideParams {
  double speed_cm_s = 10.0;
  double height_cm = 2.5;
};
double foot_slide_share(const Eigen::MatrixXd& pos, double fps, const std::vector<Leg>& legs,
                        const FootSlideParams& params = {});

// Rest: a frame is still when the mean root-relative speed of the upper body (`joints`, frame t
// from t - 1, frame 0 taking frame 1's) is below speed_cm_s. share = still frames / frames;
// longest_s = the longest run of consecutive still frames, in seconds.
struct Stillness {
  double share = 0.0;
  double longest_s = 0.0;
};
Stillness stillness(const Eigen::MatrixXd& pos, double fps, const std::vector<int>& joints, double speed_cm_s = 5.0);

// Mean over frames of the mean root-relative distance of `joints` between two motions (cm), over
// the frames both have (all joints but the root when `joints` is empty).
double motion_distance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const std::vector<int>& joints = {});

// How much a capture's poses vary: the mean root-relative distance (as motion_distance) between
// frame t and frame (t + T/2) mod T over every t, i.e. between poses half the capture apart. Two
// unrelated stretches of the capture are this far apart on average; two seeds that give the same
// motion are 0 apart.
double pose_variation(const Eigen::MatrixXd& pos, const std::vector<int>& joints = {});

// Reuse of the reference, from the graph frames the output was read from (in output order). A
// play of frame f starts wherever f is read and the frame read before was not f (a held pose is
// one play). max_plays is the most plays of one frame; coverage the share of the reference's
// `reference_frames` read at least once.
struct Reuse {
  int max_plays = 0;
  double coverage = 0.0;
};
Reuse reference_reuse(const std::vector<int>& source_frames, int reference_frames);

}  // namespace gmg
