#include "graph/continuity.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/core/error.h"
#include "engine/core/parallel.h"
#include "graph/neighbours.h"
#include "graph/pose_space.h"
#include "graph/pruning.h"

namespace gmg {

std::vector<double> continuity_thresholds(const PoseFeatures& f, const std::vector<int>& run_end,
                                          const GraphParams& params) {
  const int n = f.frame_count();
  std::vector<double> theta(static_cast<std::size_t>(n), 0.0);
  for (int l = 0; l < n; ++l) {
    const int end = run_end[static_cast<std::size_t>(l)];
    double sum = 0.0;
    int count = 0;
    for (int k = 1; k <= params.l_cn && l + k <= end; ++k, ++count) sum += pose_distance(f, l, l + k, params);
    if (count == 0) {
      for (int k = 1; k <= params.l_cn && l - k >= 0 && run_end[static_cast<std::size_t>(l - k)] == end; ++k, ++count)
        sum += pose_distance(f, l, l - k, params);
    }
    theta[static_cast<std::size_t>(l)] = count > 0 ? sum / count : 0.0;
  }
  return theta;
}

namespace {

// The memory the parallel search may give the survivors it keeps for pruning 2 (kept_survivors).
// Above exact_frames a frame searched again costs the walk of its whole leaf (graph/params.h
// kLeafWalkChecks), alone on one thread: with half this budget a 19 h build spent most of its wall
// time on one core in those searches (docs/decisions.md, "Implementation choices").
constexpr std::size_t kKeptSurvivorBytes = std::size_t{512} << 20;
// At least this many a frame however long the reference (the bound is nearly always settled among
// the first few), at most what a frame's count (one byte) holds.
constexpr std::size_t kMinKeptSurvivors = 16;
constexpr std::size_t kMaxKeptSurvivors = 255;

}  // namespace

std::size_t kept_survivors(int frames, const GraphParams& params) {
  if (params.max_transitions <= 0 || frames <= 0) return 0;
  const std::size_t k = static_cast<std::size_t>(candidate_limit(params));  // survivors are members of K_l
  const std::size_t budget = kKeptSurvivorBytes / (static_cast<std::size_t>(frames) * sizeof(Candidate));
  return std::min({k, std::max(budget, kMinKeptSurvivors), kMaxKeptSurvivors});
}

namespace {

// Every frame's pruning-1 survivors by ascending (float d, r): at most `stride` a frame in fixed
// slots (and whether the frame had more), or with stride 0 (no bound) every one in a list.
struct Survivors {
  std::size_t stride = 0;
  std::vector<Candidate> slots;  // frame l's at [l * stride, l * stride + count[l])
  std::vector<std::uint8_t> count;
  std::vector<std::uint8_t> truncated;
  std::vector<std::vector<Candidate>> lists;  // stride 0

  Survivors(int n, std::size_t kept) : stride(kept) {
    if (stride) {
      slots.resize(static_cast<std::size_t>(n) * stride);
      count.assign(static_cast<std::size_t>(n), 0);
      truncated.assign(static_cast<std::size_t>(n), 0);
    } else {
      lists.resize(static_cast<std::size_t>(n));
    }
  }
};

bool nearer(const Candidate& a, const Candidate& b) { return a.d < b.d || (a.d == b.d && a.r < b.r); }

// A frame's pruning-1 survivors of its candidates (into `out`, nearest first).
void survivors_from(const std::vector<Candidate>& candidates, int l_pn, std::vector<Candidate>& out) {
  out.clear();
  prune_runs(candidates, l_pn, out);
  std::sort(out.begin(), out.end(), nearer);
}

// One frame's pruning-1 survivors (into `out`, nearest first).
void survivors_of(const CandidateSearch& search, int l, int l_pn, CandidateScratch& scratch,
                  std::vector<Candidate>& candidates, std::vector<Candidate>& out) {
  search.find(l, scratch, candidates);
  survivors_from(candidates, l_pn, out);
}

// Pruning 2 against the edges so far, then at most max_transitions of the survivors, the nearest
// by (d in double, r), appended to `edges` by ascending target. `survivors` is nearest first by
// float d; with `complete` false it is only the first of them and this returns false, adding
// nothing, when the frames past it could still decide the bound.
bool settle_frame(int l, const Candidate* survivors, std::size_t count, bool complete, const CandidateSearch& search,
                  const GraphParams& params, const EdgeIndex& index, std::vector<Transition>& edges) {
  const std::size_t limit = static_cast<std::size_t>(params.max_transitions);
  const std::size_t first = edges.size();
  // Survivors of pruning 2, nearest first. Once `limit` are in, only those within float error of
  // the last one's distance can still rank before it in double.
  float reach = std::numeric_limits<float>::infinity();
  std::size_t passed = 0, i = 0;
  for (; i < count; ++i) {
    const Candidate& c = survivors[i];
    if (c.d > reach) break;
    if (index.covers(l, c.r, params.l_pn)) continue;
    edges.push_back({l, c.r, static_cast<double>(c.d)});
    if (limit && ++passed == limit) reach = c.d + 2.02f * search.error(c.d);
  }
  if (i == count && !complete) {
    edges.resize(first);
    return false;
  }
  for (std::size_t e = first; e < edges.size(); ++e) edges[e].weight = search.distance(l, edges[e].to);
  const auto begin = edges.begin() + static_cast<std::ptrdiff_t>(first);
  if (limit && edges.size() - first > limit) {
    const auto keep = begin + static_cast<std::ptrdiff_t>(limit);
    std::partial_sort(begin, keep, edges.end(), [](const Transition& a, const Transition& b) {
      return a.weight < b.weight || (a.weight == b.weight && a.to < b.to);
    });
    edges.erase(keep, edges.end());
  }
  std::sort(begin, edges.end(), [](const Transition& a, const Transition& b) { return a.to < b.to; });
  return true;
}

}  // namespace

std::vector<Transition> continuity_analysis(const PoseFeatures& f, const std::vector<int>& run_end,
                                            const GraphParams& params, const ContinuityProgress& progress,
                                            std::size_t kept) {
  const int n = f.frame_count();
  if (static_cast<int>(run_end.size()) != n) throw Error("continuity_analysis: run_end has the wrong size");
  if (n < 2) return {};
  const std::vector<double> theta = continuity_thresholds(f, run_end, params);
  return continuity_analysis(neighbours::PoseSpace(f, params), theta, params, progress, kept);
}

std::vector<Transition> continuity_analysis(neighbours::PoseSpace&& space, const std::vector<double>& theta,
                                            const GraphParams& params, const ContinuityProgress& progress,
                                            std::size_t kept) {
  const int n = space.frames();
  if (static_cast<int>(theta.size()) != n) throw Error("continuity_analysis: theta has the wrong size");
  std::vector<Transition> edges;
  if (n < 2) return edges;
  const CandidateSearch search(std::move(space), theta, params, params.neighbours);

  // 1. Every frame's candidates and pruning 1, in parallel and in the tree's order (each thread
  //    takes a run of neighbouring frames, whose searches read the same part of the tree).
  if (params.max_transitions <= 0)
    kept = 0;
  else if (kept == 0)
    kept = kept_survivors(n, params);
  else
    kept = std::min(kept, kMaxKeptSurvivors);
  Survivors survivors(n, kept);
  const int workers = candidate_search_workers();
  struct Work {
    CandidateScratch scratch;
    std::vector<Candidate> candidates, kept;
    std::vector<CandidateScratch> run_scratch;
    std::vector<std::vector<Candidate>> run;
  };
  std::vector<Work> work(static_cast<std::size_t>(workers));
  const std::vector<int>& order = search.query_order();
  constexpr std::size_t kChunk = 512, kRun = 64;  // kRun: frames searched at a time (find_run)
  const std::size_t chunks = (static_cast<std::size_t>(n) + kChunk - 1) / kChunk;
  std::atomic<std::size_t> chunks_done{0};
  parallel_for(chunks, workers, [&](std::size_t chunk, int worker) {
    Work& w = work[static_cast<std::size_t>(worker)];
    const std::size_t chunk_end = std::min(static_cast<std::size_t>(n), (chunk + 1) * kChunk);
    for (std::size_t q = chunk * kChunk; q < chunk_end; ++q) {
      const std::size_t i = (q - chunk * kChunk) % kRun;
      if (i == 0)
        search.find_run(static_cast<int>(q), static_cast<int>(std::min(kRun, chunk_end - q)), w.run_scratch, w.run);
      const int l = order[q];
      survivors_from(w.run[i], params.l_pn, w.kept);
      const std::size_t fl = static_cast<std::size_t>(l);
      if (survivors.stride == 0) {
        survivors.lists[fl] = w.kept;
        continue;
      }
      const std::size_t m = std::min(survivors.stride, w.kept.size());
      std::copy(w.kept.begin(), w.kept.begin() + static_cast<std::ptrdiff_t>(m),
                survivors.slots.begin() + static_cast<std::ptrdiff_t>(fl * survivors.stride));
      survivors.count[fl] = static_cast<std::uint8_t>(m);
      survivors.truncated[fl] = w.kept.size() > m ? 1 : 0;
    }
    const std::size_t done = ++chunks_done;
    if (done % 64 == 0) search.store().release();  // the positions read in double, when spilled
    if (progress && worker == 0) progress(static_cast<int>(std::min(static_cast<std::size_t>(n), done * kChunk)), n);
  });

  // 2. Pruning 2 and the bound, in frame order: pruning 2 looks at the edges of earlier frames.
  if (params.max_transitions > 0)
    edges.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(std::min(params.max_transitions, 8)));
  EdgeIndex index(n);
  Work& w = work.front();
  for (int l = 0; l < n; ++l) {
    const std::size_t fl = static_cast<std::size_t>(l);
    const std::size_t first = edges.size();
    if (survivors.stride == 0) {
      settle_frame(l, survivors.lists[fl].data(), survivors.lists[fl].size(), true, search, params, index, edges);
      std::vector<Candidate>().swap(survivors.lists[fl]);
    } else if (!settle_frame(l, survivors.slots.data() + fl * survivors.stride, survivors.count[fl],
                             survivors.truncated[fl] == 0, search, params, index, edges)) {
      survivors_of(search, l, params.l_pn, w.scratch, w.candidates, w.kept);  // all of them, this time
      settle_frame(l, w.kept.data(), w.kept.size(), true, search, params, index, edges);
    }
    // This frame's edges join the index after all of its candidates were tested.
    for (std::size_t e = first; e < edges.size(); ++e) index.add(l, edges[e].to);  // ascending
    if (l % 32768 == 32767) search.store().release();
  }
  if (progress) progress(n, n);
  return edges;
}

}  // namespace gmg
