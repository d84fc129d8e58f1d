// A budgeted search's lists handed on between consecutive frames (bench_flann --propagate): how
// much of the exact candidates a frame's neighbours' lists give it, and at what cost.
#pragma once

#include <algorithm>
#include <vector>

#include "graph/candidate_gathering.h"
#include "graph/neighbours.h"
#include "graph/pose_space.h"
#include "tests/bench_flann_methods.h"
#include "tests/benchmark_support.h"

namespace gmg::flann_bench {

// A budgeted search's lists handed on between consecutive query frames: a frame's candidates are
// mostly runs of consecutive frames, so a member r of frame l's K_l suggests r + 1 for frame l + 1
// (and r - 1 for l - 1). A forward pass over each block (frame i takes its own list and frame
// i - 1's, each member shifted a frame on and widened by `width` frames either side), then a
// backward one (frame i + 1's, shifted a frame back), each list refined as K_l is defined
// (FastRefiner: exact over the frames offered). The cost is fixed per frame, whatever the length.
// `chained` false: one pass in which each frame takes its two neighbours' own lists (as found, not
// as passed on), so that a frame's result does not depend on the order frames are taken in.
// out_fresh: frames offered beyond the lists they were added to, per query frame (both passes).
inline Lists propagate(const Reference& ref, const neighbours::PoseSpace& space, const Lists& found, int width,
                       bool chained, Row& row, double& out_fresh) {
  const FastRefiner refine{ref, space};
  const int n = ref.features.frame_count();
  Lists out = found;
  std::vector<int> offered;
  auto offer = [&](const std::vector<int>& from, int shift) {
    for (const int r : from)
      for (int d = -width; d <= width; ++d) {
        const int c = r + shift + d;
        if (c >= 0 && c < n) offered.push_back(c);
      }
  };
  // Frames offered beyond a frame's own list: the distances a pass that kept the list's own would
  // have to make.
  std::size_t fresh = 0;
  auto settle = [&](std::size_t i, std::size_t own) {
    std::sort(offered.begin(), offered.end());
    offered.erase(std::unique(offered.begin(), offered.end()), offered.end());
    fresh += offered.size() - own;
    refine(ref.frames[i], offered.data(), nullptr, static_cast<int>(offered.size()), out[i]);
  };
  auto pass = [&](std::size_t i, std::size_t from, int shift) {
    offered = out[i];
    offer(out[from], shift);
    settle(i, out[i].size());
  };
  Timer t;
  if (chained) {
    for (std::size_t i = 1; i < ref.frames.size(); ++i)
      if (ref.frames[i] == ref.frames[i - 1] + 1) pass(i, i - 1, 1);
    for (std::size_t i = ref.frames.size() - 1; i-- > 0;)
      if (ref.frames[i + 1] == ref.frames[i] + 1) pass(i, i + 1, -1);
  } else {
    for (std::size_t i = 0; i < ref.frames.size(); ++i) {
      offered = found[i];
      if (i > 0 && ref.frames[i] == ref.frames[i - 1] + 1) offer(found[i - 1], 1);
      if (i + 1 < ref.frames.size() && ref.frames[i + 1] == ref.frames[i] + 1) offer(found[i + 1], -1);
      settle(i, found[i].size());
    }
  }
  row.refine_s = t.cpu();
  out_fresh = ref.frames.empty() ? 0.0 : static_cast<double>(fresh) / static_cast<double>(ref.frames.size());
  return out;
}

// The neighbours' pass (propagate, not chained, width 0) as a build would make it: each frame's own
// members keep the distances the search gave them (made here before the clock starts), and only the
// frames its neighbours offer beyond them are measured, into one reused gathering. Returns the
// lists; row.refine_s is the pass's CPU.
inline Lists propagate_lean(const Reference& ref, const neighbours::PoseSpace& space, const Lists& found, Row& row) {
  const neighbours::Allowed allowed{ref.params.l_pn, ref.params.exclude_near};
  const std::size_t k = static_cast<std::size_t>(candidate_limit(ref.params));
  const std::size_t q = ref.frames.size();
  std::vector<std::vector<Candidate>> own(q);
  for (std::size_t i = 0; i < q; ++i)
    for (const int r : found[i]) own[i].push_back({space.approx(ref.frames[i], r), r});
  Lists out(q);
  std::vector<Candidate> items, result;
  std::vector<int> fresh;
  std::vector<float> kth;
  std::vector<std::pair<double, int>> ties;
  Timer t;
  for (std::size_t i = 0; i < q; ++i) {
    const int l = ref.frames[i];
    const double theta = ref.theta[static_cast<std::size_t>(l)];
    neighbours::Gathered g(space, k, space.radius(theta), items, kth, ties);
    if (g.radius() < 0) continue;
    for (const Candidate& c : own[i]) g.add(c.d, c.r);
    const std::vector<int>& mine = found[i];  // ascending
    fresh.clear();
    auto offer = [&](const std::vector<int>& from, int shift) {
      for (const int f : from) {
        const int r = f + shift;
        if (r >= 0 && r < ref.features.frame_count() && allowed(l, r) &&
            !std::binary_search(mine.begin(), mine.end(), r))
          fresh.push_back(r);
      }
    };
    if (i > 0 && ref.frames[i - 1] == l - 1) offer(found[i - 1], 1);
    if (i + 1 < q && ref.frames[i + 1] == l + 1) offer(found[i + 1], -1);
    std::sort(fresh.begin(), fresh.end());
    fresh.erase(std::unique(fresh.begin(), fresh.end()), fresh.end());
    for (const int r : fresh) {
      const float d = space.approx(l, r);
      if (d <= g.radius() && space.within(l, r, d, theta)) g.add(d, r);
    }
    g.resolve(l, result);
    for (const Candidate& c : result) out[i].push_back(c.r);
  }
  row.refine_s = t.cpu();
  return out;
}

}  // namespace gmg::flann_bench
