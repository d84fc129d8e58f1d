// The continuous capture runs of a source motion: which frames are naturally followed by the next
// one, so that it is read at fractional times, differenced and analysed without crossing a break.
//
// A source is described by its break frames, the frames not naturally followed by the next (a
// clip's last frame, a capture jump): a handful per reference whatever its length, so the runs of
// an hour of motion cost a few integers, and every question is a binary search among them. Shared
// by the assembly's readers (engine/assemble/timeline.h), the per-reference analysis that the
// graph stores (engine/motion/capture_facts.h) and the planner's run ends.
#pragma once

#include <vector>

namespace gmg {

class CaptureRuns {
 public:
  CaptureRuns() = default;
  // `frames` frames; `breaks` the frames not followed naturally by the next, ascending, each in
  // [0, frames) (gmg::Error otherwise).
  CaptureRuns(int frames, std::vector<int> breaks);
  // From a flag per frame: `continues[f]` says frame f is naturally followed by f + 1.
  explicit CaptureRuns(const std::vector<char>& continues);

  int frame_count() const { return frames_; }
  const std::vector<int>& breaks() const { return breaks_; }

  // Frame f (in [0, frame_count)) is naturally followed by f + 1: it is not a break. (The last
  // frame may be declared continuing; readers still check f + 1 < frame_count.)
  bool continues(int f) const;
  // The first and last frames of the run holding f: after the previous break (or 0), and the
  // next break at or after f (or the last frame).
  int first(int f) const;
  int last(int f) const;

  // Whether time t can be read (interpolated) inside the capture run of frame `from`.
  bool readable(double t, int from) const;

  // The time a velocity at t is differenced against, at `rate` source frames per output frame:
  // t - rate inside its run (out_sign 1), else t + rate at the run's start (out_sign -1). False for
  // a held frame (rate <= 0) or a run too short for either.
  bool velocity_partner(double t, double rate, double& out_time, double& out_sign) const;

  // The frame time f + a (0 <= a < 1) is interpolated towards: f + 1 when a > 0 and f continues
  // into it, else f itself.
  int next_frame(int f, double a) const { return a > 0.0 && f + 1 < frames_ && continues(f) ? f + 1 : f; }

 private:
  int frames_ = 0;
  std::vector<int> breaks_;
};

}  // namespace gmg
