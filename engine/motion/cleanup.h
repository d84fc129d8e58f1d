// Optional clean-up of reference motion (SPEC "Motion representation"; the paper's GENEA 2023
// setup): for named joints, lock yaw and pitch and smooth roll with a Savitzky-Golay filter.
//
// "Roll" is the twist about the joint's bone axis (the direction of its first child's offset,
// else its End Site, else its own offset); "yaw and pitch" are the rest of the rotation (the
// swing). Locking sets the swing to the rest pose's (none), keeping only the twist, whose angle
// is then unwrapped and smoothed over time.
#pragma once

#include <string>
#include <vector>

#include "engine/motion/motion.h"

namespace gmg {

struct CleanupParams {
  // Reference clips' joints whose yaw and pitch are locked and roll smoothed (engine/cleanup.h);
  // empty = off, the default. The paper's GENEA 2023 setup names the four wrist joints.
  std::vector<std::string> lock_joints;
  int smooth_window = 15;  // Savitzky-Golay window (odd), the paper's value
  int smooth_order = 3;    // Savitzky-Golay polynomial order, the paper's value
};

// Throws gmg::Error naming the first key out of range.
void cleanup_params_validate(const CleanupParams& params);

// scipy.signal.savgol_filter(x, window, order, mode="interp"): a least-squares polynomial of
// the given order over each centred window; the first and last window/2 samples are taken from
// the polynomial fitted to the first and last window. Requires an odd window > order; a signal
// shorter than the window uses the largest odd window that fits (unchanged if none > order).
std::vector<double> savgol_filter(const std::vector<double>& x, int window, int order);

// Applies the clean-up to the named joints of m in place. `what` names m in errors (an
// unknown joint name is an error).
void motion_lock_and_smooth(Motion& m, const std::vector<std::string>& joints, int window, int order,
                            const std::string& what);

// The unit bone axis used as the twist axis of joint j.
glm::dvec3 bone_axis(const Skeleton& skeleton, int j);

}  // namespace gmg
