// Assembly by source time: where each output frame is read from.
//
// A plan is a list of pieces, each a path of source frames stretched or squeezed onto its target
// length. Instead of resampling each piece on its own and joining the pieces, the output is
// mapped to a continuous source time: frame i of a piece reads its path at position
// x = i * (n - 1) / (L - 1), inside the run of consecutive source frames that holds floor(x), so
// a path that walks naturally plays as one stretch of capture at the piece's warp rate. Every
// place where the source does not continue naturally, a junction that did not continue or an
// unnatural edge inside a path, starts a new run: that is a transition (engine/assemble/transitions.h).
#pragma once

#include <vector>

namespace gmg {

// One piece of the plan: graph frames (>= 1) and the output frames they fill (>= 1).
struct PathPiece {
  std::vector<int> path;
  int length = 1;
};

struct SourceClock {
  double time = 0.0;  // source frame time (fractional: between floor(time) and the next frame)
  double rate = 1.0;  // source frames per output frame here (the piece's warp rate; 0 for a held frame)
  int run = 0;        // increases at every transition; equal runs are one continuous stretch
};

// The continuous capture runs of a source (`continues[f]`: frame f is naturally followed by f + 1),
// for reading it at fractional times without crossing a break. Shared by the pose reader of
// transitions.cpp and the channel reader of channels.cpp, so both read exactly alike.
class CaptureRuns {
 public:
  // Keeps a reference to `continues`, which must outlive it.
  explicit CaptureRuns(const std::vector<char>& continues);

  // Whether time t can be read (interpolated) inside the capture run of frame `from`.
  bool readable(double t, int from) const;

  // The time a velocity at t is differenced against, at `rate` source frames per output frame:
  // t - rate inside its run (out_sign 1), else t + rate at the run's start (out_sign -1). False for
  // a held frame (rate <= 0) or a run too short for either.
  bool velocity_partner(double t, double rate, double& out_time, double& out_sign) const;

  // The frame time f + a (0 <= a < 1) is interpolated towards: f + 1 when a > 0 and f continues
  // into it, else f itself.
  int next_frame(int f, double a) const {
    return a > 0.0 && f + 1 < static_cast<int>(continues_.size()) && continues_[static_cast<std::size_t>(f)] ? f + 1
                                                                                                             : f;
  }

 private:
  const std::vector<char>& continues_;
  std::vector<int> first_;  // first_[f]: the first frame of the run holding f
};

// `continues[f]` says whether source frame f is naturally followed by f + 1 (not a break node).
// One clock per output frame (the sum of the pieces' lengths).
std::vector<SourceClock> source_timeline(const std::vector<PathPiece>& pieces, const std::vector<char>& continues);

}  // namespace gmg
