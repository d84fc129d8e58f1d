// The user's control over a reenactment (ours): pins, which play a stretch of the reference at a
// moment of the output, and kept motion, which regenerates only some time ranges of an earlier
// output and keeps every other frame of it exactly.
//
// Both are splices: a stretch of one motion put into another, joined at its two ends by
// inertialization inside the stretch (engine/assemble/inertialize.h): at the stretch's first frame
// the difference between the two motions, in pose and velocity, becomes an offset that a
// critically damped spring takes to zero going forward; at its last frame the same going backward.
// So the output is continuous where it enters and leaves the stretch, and plays the stretch's own
// motion once the springs have settled.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/motion/body_layers.h"
#include "engine/motion/motion.h"
#include "engine/motion/npz.h"
#include "graph/motion_graph.h"
#include "search/anchors.h"

namespace gmg {

// One --pin: at output time `at` (seconds) play the reference from `from` to `to` seconds, on the
// timeline of `clip` (a clip's name, as `gmg inspect` lists them), or of the whole graph ("").
// `word` >= 0 (--pin-word) puts the stretch where the transcript's word number `word` starts
// instead of at `at` (resolve_word_pins).
struct PinRequest {
  double at = 0.0;
  std::string clip;
  double from = 0.0, to = 0.0;
  int word = -1;
};

// A time range [from, to) of the output, in seconds, that is planned afresh.
using TimeRange = std::pair<double, double>;

// What the user fixes: pins, and an earlier output to keep outside `ranges`.
struct Control {
  std::vector<PinRequest> pins;
  const Motion* keep = nullptr;          // the earlier output (in the graph's skeleton, the reference's up axis)
  const SmplxBody* keep_body = nullptr;  // its face, when it has one (an .npz): kept like the motion
  std::string keep_name;                 // its file, for errors
  std::vector<TimeRange> ranges;
};

// The same in output frames, checked: what reenact_events takes.
struct ControlFrames {
  std::vector<Anchor> pins;                 // pin_anchors
  const Motion* keep = nullptr;             // may be null: nothing kept
  const SmplxBody* keep_body = nullptr;     // may be null
  std::vector<std::pair<int, int>> ranges;  // range_frames
};

// Parses "T=FROM:TO" or "T=CLIP@FROM:TO" (and for --pin-word "N=FROM:TO", word = N). Throws
// gmg::Error naming `option` and the text when it is not of that form.
PinRequest parse_pin(const std::string& text, const std::string& option, bool by_word);
// Parses "FROM:TO" (seconds, FROM < TO).
TimeRange parse_range(const std::string& text, const std::string& option);

// The pins' output frames and graph frames at `fps`: each starts at round(at * fps) and plays
// round((to - from) * fps) graph frames from round(from * fps) of its clip (or of the graph).
// Throws gmg::Error naming `speech` (the audio) for a pin that leaves the output of total_frames,
// and naming `graph_name` for one outside the graph or its clip, across a capture break, of no
// frame, or naming no clip of it; and for pins that overlap. Sorted by start.
std::vector<Anchor> pin_anchors(const MotionGraph& g, const std::vector<PinRequest>& pins, int total_frames,
                                const std::string& speech, const std::string& graph_name);

// The rests that do not overlap a pin, with the pins, sorted by start (place_anchors' order).
std::vector<Anchor> with_pins(const std::vector<Anchor>& rests, const std::vector<Anchor>& pins);

// The pins' word times: each pin with word >= 0 gets `at` = the start of that word of `words`
// (sorted, as `gmg analyse` counts them from 0). Throws gmg::Error naming `transcript` when there
// are no words or the number is past the last word.
void resolve_word_pins(std::vector<PinRequest>& pins, const std::vector<double>& word_starts,
                       const std::string& transcript);

// Puts `insert` (length b - a frames, same skeleton) into `base` at frames [a, b), joined at both
// ends by springs of `halflife` frames: frame a (when a > 0) and frame b - 1 (when b < frame count)
// are base's, moving as base moves there, so the output runs on from base's frame a - 1 into the
// insert and from it into base's frame b. Joints
// with mask[j] == 0 keep base's values throughout (empty mask: every joint is spliced).
void splice_motion(Motion& base, const Motion& insert, int a, int b, double halflife, const std::vector<char>& mask);

// Each pin played as the reference's whole body in `out` (Y-up, the graph's skeleton), turned and
// moved on the floor to start where the output's root is, facing its way, and joined within
// `settle` frames of the pin's ends.
void apply_pins(Motion& out, const MotionGraph& g, const std::vector<Anchor>& pins, int settle);

// The output frames the ranges cover, [first, last) each, sorted and merged; throws gmg::Error
// naming `name` (the earlier output) for a range that is empty or leaves the output.
std::vector<std::pair<int, int>> range_frames(const std::vector<TimeRange>& ranges, double fps, int total_frames,
                                              const std::string& name);

// Throws gmg::Error naming control.keep_name when the kept motion is not in g's skeleton, not at its
// frame rate, or not exactly total_frames long.
void check_keep(const Control& control, const MotionGraph& g, int total_frames);

// The earlier output kept outside `frames` (range_frames): `out` (the new reenactment, in the
// reference's up axis) takes every value of `keep` outside them, and inside them its upper body
// over keep's lower body (when layered), joined to keep at both ends by springs of `halflife`
// frames.
void apply_keep(Motion& out, const Motion& keep, const std::vector<std::pair<int, int>>& frames, const MotionGraph& g,
                const BodyLayers& layers, double spine_follow, double halflife);

// The face of the earlier output kept outside `frames` as apply_keep keeps its motion: `face` (the
// new reenactment's) takes keep's expressions outside them and inside them is joined to keep's at
// both ends by springs of `halflife` frames. Nothing when either has no face or their sizes differ.
void apply_keep_face(SmplxBody& face, const SmplxBody& keep, const std::vector<std::pair<int, int>>& frames,
                     double halflife);

// The report's "control": {kept: [[first, last), ...], planned: [...], pinned: [{start_frame,
// frames, graph_frame}]} in output frames, and each subsequence of report["subsequences"] marked
// "control": "kept", "planned" or "pinned". Nothing when there is neither keep nor pin.
void control_report(nlohmann::ordered_json& report, const std::vector<std::pair<int, int>>& planned, int total_frames,
                    bool keeping, const std::vector<Anchor>& pins);

}  // namespace gmg
