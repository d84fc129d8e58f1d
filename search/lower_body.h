// The lower body's own path (ours; the layered body of engine/motion/body_layers.h): the root, hips
// and legs play long contiguous stretches of the reference, so the feet stay where the capture
// puts them and the knees bend as the speaker's did, and change stretch only where a person shifts
// weight: with both feet planted and the hips slow (engine/motion/stance.h).
//
// A stretch plays on until one of three things asks for a change:
// - a pause of the new speech (rest_min_s or longer) is coming and the stretch would not be still
//   there: the change, at the last stance frame of the rest_lead_s before the pause, goes to a stance
//   from which the reference rests for as long as the pause, up to as long as the reference itself
//   ever rests (the rest is held as long as the speaker holds one, no longer);
// - its capture run ends (a clip's end): the change goes to a stance with a long run ahead;
// - nothing else: the speaker's own weight shifts play as captured, at the speaker's own rate.
// Every change goes to the stance nearest the one it leaves (feet, hips' height and tilt in the
// hips' heading frame), among stretches not played too often (the reuse cap) and not withheld by the
// seed (variety, as the upper body's planner), nearest first, drawn among near-equal ones.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "engine/core/enum_names.h"
#include "engine/motion/capture_runs.h"
#include "engine/motion/stance.h"

namespace gmg {

struct LowerBodyParams {
  double rest_min_s = 0.5;   // test pauses at least this long rest the lower body ((0, 10])
  double rest_lead_s = 0.7;  // a change into a rest comes at most this long before the pause ((0, 5])
  int reuse_cap_plays = 3;   // a stretch played this often is not played again (0: no cap)
  double variety = 0.3;      // share of the reference's seconds a seed withholds as targets ([0, 0.9])
};

enum class LowerChange : std::uint8_t { Start, Rest, RunEnd };
inline constexpr EnumName<LowerChange> kLowerChangeNames[] = {
    {LowerChange::Start, "start"}, {LowerChange::Rest, "rest"}, {LowerChange::RunEnd, "run_end"}};

// Output frames [start, start + length) play graph frames source, source + 1, ...
struct LowerSegment {
  int start = 0;
  int length = 0;
  int source = 0;
  LowerChange change = LowerChange::Start;  // why the stretch starts here
  double gap = 0.0;                         // stance distance from where the previous one was (leg lengths)
};

struct LowerPlan {
  std::vector<LowerSegment> segments;  // consecutive, covering the output
};

// The output frames that rest: runs of `pause` (per output frame, 0..1, audio::pause_weight of the
// new speech) at or above 0.5 lasting rest_min_s or longer, as [first, last) pairs.
std::vector<std::pair<int, int>> rest_windows(const std::vector<float>& pause, double fps, double rest_min_s);

// Plans `total_frames` output frames (>= 0). `stance` known, over `runs`' frames. `pause` holds
// total_frames values (or none: no rests). Draws from rng (the job's generator).
LowerPlan plan_lower_body(const Stance& stance, const CaptureRuns& runs, const std::vector<float>& pause,
                          int total_frames, double fps, const LowerBodyParams& params, std::mt19937_64& rng);

}  // namespace gmg
