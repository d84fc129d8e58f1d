// The lower body's own path (ours; the layered body of engine/motion/body_layers.h): the root, hips
// and legs play long contiguous stretches of the reference, so the feet stay where the capture
// puts them and the knees bend as the speaker's did, and change stretch only where a person shifts
// weight: with both feet planted and the hips slow (engine/motion/stance.h).
//
// A stretch plays on until one of three things asks for a change:
// - a rest of the output (search/anchors.h: where the new speech pauses) is coming and the stretch
//   would not be still there: a change at a stance frame of the few seconds before the rest, to a
//   stance from which the reference's legs stay still for as long as the rest, when that saves more
//   stillness than the change itself costs;
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
#include "search/anchors.h"

namespace gmg {

struct LowerBodyParams {
  int reuse_cap_plays = 3;  // a stretch played this often is not played again (0: no cap)
  double variety = 0.3;     // share of the reference's seconds a seed withholds as targets ([0, 0.9])
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

// Plans `total_frames` output frames (>= 0). `stance` known, over `runs`' frames. `rests` are the
// output's rests (search/anchors.h rest_anchors; others are ignored), the same the upper body
// plays still stretches in. Draws from rng (the job's generator).
LowerPlan plan_lower_body(const Stance& stance, const CaptureRuns& runs, const std::vector<Anchor>& rests,
                          int total_frames, double fps, const LowerBodyParams& params, std::mt19937_64& rng);

}  // namespace gmg
