// Where and how the reference stands, frame by frame: what the lower body's planner
// (search/lower_body.h) needs to change stance only where a person would (both feet planted, the
// hips slow) and to rest where the speech rests. Computed once per reference, from the lower
// layer's joints only (engine/motion/body_layers.h).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/motion/body_layers.h"
#include "engine/motion/capture_runs.h"
#include "engine/motion/motion.h"
#include "engine/motion/samples.h"

namespace gmg {

// A stance frame has both feet in contact (engine/motion/capture_facts.h foot_contacts) and the
// hips moving horizontally slower than this many leg lengths a second (7 cm/s for a 0.9 m leg: a
// weight shift moves them 15-40 cm/s).
constexpr double kStanceHipSpeed = 0.08;

// Per frame, what a stance looks like (kStanceDims values, in leg lengths, in the hips' heading
// frame so that a speaker facing elsewhere stands the same): each foot end's position relative to
// the hip branch (x, y, z), the hips' height above the lowest foot point of the capture run, and
// the pelvis's tilt (its swing's image of +Y, x and z).
constexpr int kStanceDims = 9;

struct Stance {
  bool known = false;       // false: the skeleton has no two legs (nothing is layered)
  double leg_length = 0.0;  // hip branch to foot end in the first frame, file units
  // Owned, or read in place from a graph file (engine/motion/samples.h).
  Samples<float> pose;            // frames x kStanceDims
  Samples<float> place;           // frames x 2: the hips' horizontal position (x, z), leg lengths
  Samples<float> speed;           // per frame: the largest speed of a leg joint relative to the hips, leg lengths/s
  Samples<std::uint8_t> planted;  // per frame: 1 for a stance frame
  // The lower body is still at a frame when `speed` is below this, the reference's 35th percentile:
  // where the whole body is still (its largest joint speed below its own 5th percentile: BEAT2 17
  // cm/s, ZEGGS 8 cm/s) the legs move at their 35th-40th percentile.
  float still_speed = 0.0f;
};

// Computes it over every frame of m (Y-up) with layers found in m (find_body_layers).
Stance stance_facts(const Motion& m, const CaptureRuns& runs, const BodyLayers& layers);

// The squared distance of two frames' stance poses.
inline double stance_distance(const Stance& s, int a, int b) {
  double sum = 0.0;
  for (int d = 0; d < kStanceDims; ++d) {
    const double x =
        static_cast<double>(s.pose[static_cast<std::size_t>(a) * kStanceDims + static_cast<std::size_t>(d)]) -
        static_cast<double>(s.pose[static_cast<std::size_t>(b) * kStanceDims + static_cast<std::size_t>(d)]);
    sum += x * x;
  }
  return sum;
}

}  // namespace gmg
