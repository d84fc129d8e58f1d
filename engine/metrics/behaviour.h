// Seeds that give the same motion: the distance between two outputs, and the capture's own pose
// variation that scales it. (Sliding feet, rests and reuse are in lifelike.h and played_paths.h.)
//
// Positions are frames x (3 * joints) in centimetres (engine/metrics/evaluate.h
// length_unit_to_cm), joint 0 the root.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace gmg {

// Mean over frames of the mean root-relative distance of `joints` between two motions (cm), over
// the frames both have (all joints but the root when `joints` is empty).
double motion_distance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const std::vector<int>& joints = {});

// How much a capture's poses vary: the mean root-relative distance (as motion_distance) between
// frame t and frame (t + T/2) mod T over every t, i.e. between poses half the capture apart. Two
// unrelated stretches of the capture are this far apart on average; two seeds that give the same
// motion are 0 apart.
double pose_variation(const Eigen::MatrixXd& pos, const std::vector<int>& joints = {});

}  // namespace gmg
