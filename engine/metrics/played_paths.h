// What a reenactment played, read from its report: the upper body's path pieces (`subsequences`)
// and the lower body's stretches (`lower_body.stretches`), and the metrics of how they were cut
// and reused: junctions, stance changes, plays of one reference frame, jumps back to something
// just played. The motion's own lifelike metrics are in lifelike.h.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/metrics/lifelike.h"

namespace gmg {

// Output frames [start_frame, start_frame + length) play the graph frames `path`, resampled evenly:
// path index i of n lands at output frame start_frame + i * (length - 1) / (n - 1).
struct PlayedSegment {
  int start_frame = 0;
  int length = 0;
  std::vector<int> path;
  bool continued = false;        // starts at the previous segment's natural successor: no junction
  int transitions_inside = 0;    // unnatural edges inside the path
  double junction_gap_cm = 0.0;  // the pose gap of its junction (largest root-relative joint distance)
};

struct PlayedPaths {
  std::vector<PlayedSegment> upper;  // the subsequences, in output order
  // The lower body's stretches (continued and transitions_inside unused); empty when the report
  // has no layered body: then the whole body plays the upper path.
  std::vector<PlayedSegment> lower;
  int stance_changes = 0;  // stretches whose change is not "start"
};

// Reads a `gmg reenact` report. gmg::Error naming `name` when it has no subsequences, or a
// subsequence or stretch lacks or mistypes a field the metrics read (start_frame, target_length or
// length, graph_ranges as [first, last] pairs, continued, transitions_inside, junction_gap_cm).
PlayedPaths played_paths_of(const nlohmann::json& report, const std::string& name);
PlayedPaths played_paths_of(const nlohmann::ordered_json& report, const std::string& name);

// The graph frames the segments read, in output order.
std::vector<int> played_frames(const std::vector<PlayedSegment>& segments);

// Back-jumps: pieces of the path (maximal runs of consecutive graph frames, a new one at each
// segment) that start at a graph frame last played less than window_s seconds of output earlier,
// where the piece is not the natural continuation of the piece before (its first frame is not the
// previous frame + 1). A held frame played again counts. Output times as PlayedSegment says.
int back_jumps(const std::vector<PlayedSegment>& segments, double fps, double window_s);

// Reuse of the reference from the graph frames read in output order (played_frames). A play of
// frame f starts wherever f is read and the frame read before was not f (a held pose is one
// play). max_plays is the most plays of one frame. coverage is the share of the reference's
// `reference_frames` read at least once; with reference_frames <= 0 it is not known (0).
struct Reuse {
  int max_plays = 0;
  double coverage = 0.0;
};
Reuse reference_reuse(const std::vector<int>& source_frames, int reference_frames);

// The path metrics of one output of `duration_s` seconds at `fps`.
struct LifelikePaths {
  static constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();
  // Upper body: junctions = subsequences after the first that did not continue, plus every
  // transition inside a path (the first's included); per minute of output.
  int junctions = 0;
  double junctions_per_min = 0.0;
  double junction_gap_median_cm = kUndefined;  // median junction_gap_cm of the subsequence junctions
  // Lower body: stance changes per minute; without a layered body every junction moves the legs
  // too, so it is junctions_per_min.
  double stance_changes_per_min = 0.0;
  int max_plays_upper = 0, max_plays_lower = 0;    // reference_reuse of each layer
  int back_jumps_upper = 0, back_jumps_lower = 0;  // back_jumps of each layer
};
LifelikePaths lifelike_paths(const PlayedPaths& paths, double fps, double duration_s, const LifelikeParams& params);

}  // namespace gmg
