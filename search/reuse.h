// Reuse of the reference (SPEC "Reuse"): a reference frame played recently costs more, so the
// planner does not replay one attractive stretch while others lie unused.
//
// Each frame keeps a play count that decays with output time (half-life halflife frames); a
// frame costs the square of its count (a third play of a stretch costs four times a second) and a
// candidate pays its most played frame. A stretch just played costs about 1 per play,
// one played a half-life ago half that, and so does a stretch that shares only some frames with it:
// a short popular stretch (an onset-ended gesture) replayed inside ever different paths was what
// the mean over a path's frames let through (4-6 plays of its frames in a minute).
//
// The decayed count prices a replay against what it saves, so a stretch that alone suits many
// pauses was still played a fourth time in a minute when its count had decayed just enough. The
// cap is exact: a frame already played cap_plays times within the last cap_window output frames
// costs kCapCost more, far above any speech distance or junction it could save.
#pragma once

#include <memory>
#include <vector>

namespace gmg {

class ReuseTracker {
 public:
  // The cap's cost, in the units of frame_cost (reuse_weight times it is paid).
  static constexpr double kCapCost = 100.0;

  // frames: the graph's frame count; halflife in output frames (> 0); cap_plays (0 = no cap)
  // plays within cap_window output frames.
  ReuseTracker(int frames, double halflife, int cap_plays = 0, int cap_window = 0, int return_window = 0);

  // The frames of a committed path, played from output frame `time` on.
  void play(const std::vector<int>& path, int time);

  // Frame f's decayed play count at output frame `time`.
  double plays(int f, int time) const;

  // Whether frame f has had cap_plays plays within cap_window output frames before `time`, or was
  // played within return_window output frames before it (a jump back into what was just played:
  // the same gesture twice within seconds reads as a stutter, not as a speaker's habit).
  bool capped(int f, int time) const {
    const Block* b = block(f);
    if (!b) return false;
    const std::size_t k = static_cast<std::size_t>(f % kBlock);
    if (return_window_ > 0 && b->count[k] > 0.0 && b->last[k] > time - return_window_) return true;
    if (cap_plays_ <= 0) return false;
    // recent holds f's last cap_plays play times, oldest first.
    return b->recent[k * static_cast<std::size_t>(cap_plays_)] > time - cap_window_;
  }

  // Its cost: plays squared, plus kCapCost when capped.
  double frame_cost(int f, int time) const {
    const double p = plays(f, time);
    return p * p + (capped(f, time) ? kCapCost : 0.0);
  }

  // Whether a path comes back to a frame it played (a loop through transitions; a held frame is
  // one play): the same stroke twice within seconds.
  static bool loops(const std::vector<int>& path);

  // The largest frame_cost over a path's frames.
  double path_cost(const std::vector<int>& path, int time) const;

  // For every frame s of `frames`: the largest frame_cost of s, s + 1, ..., s + window - 1
  // (clamped to the graph).
  void window_costs(int window, int time, const std::vector<int>& frames, std::vector<double>& out) const;

 private:
  // The play counts are kept for blocks of kBlock frames, a block made when one of its frames is
  // first played: a reenactment plays a few thousand frames of a reference of any length, so the
  // tracker costs no work or memory per reference frame.
  static constexpr int kBlock = 4096;
  struct Block {
    std::vector<double> count;  // at time last[f]
    std::vector<int> last;
    std::vector<int> recent;  // per frame, its last cap_plays_ play times, oldest first
  };
  const Block* block(int f) const { return blocks_[static_cast<std::size_t>(f / kBlock)].get(); }
  Block& block_to_play(int f);

  int frames_;
  double decay_per_frame_;  // ln 2 / halflife
  int cap_plays_;
  int cap_window_;
  int return_window_;
  std::vector<std::unique_ptr<Block>> blocks_;
};

}  // namespace gmg
