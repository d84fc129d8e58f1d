// Path resampling (paper A.1.2): an accepted path stretched or squeezed to its target length.
#pragma once

#include <vector>

#include "engine/motion/motion.h"

namespace gmg {

// Frames of `source` at the path's frames, resampled evenly to exactly `length` frames
// (SLERP for rotations, linear for translations between neighbouring path frames).
Motion resample_path(const Motion& source, const std::vector<int>& path, int length);

}  // namespace gmg
