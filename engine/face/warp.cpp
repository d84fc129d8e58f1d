#include "engine/face/warp.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace gmg {
namespace {

// Reference time of output time t under unit u's stretch c, kept between the first and the last
// reference frame inside the stretch (frames at ceil(start) .. ceil(end) - 1; the nearest frame for
// a stretch shorter than a frame) and inside its clip: a unit shows its own phone's face, never
// its neighbour's.
double warped(const ReferenceFace& r, const FaceUnit& u, const FaceCandidate& c, double t) {
  const double rate = (c.end - c.start) / (u.end - u.start);
  double lo = std::ceil(c.start), hi = std::ceil(c.end) - 1.0;
  if (hi < lo) lo = hi = std::round(0.5 * (c.start + c.end));
  lo = std::max(lo, static_cast<double>(r.clip_first[static_cast<std::size_t>(c.clip)]));
  hi = std::min(hi, static_cast<double>(r.clip_end[static_cast<std::size_t>(c.clip)] - 1));
  return std::clamp(c.start + (t - u.start) * rate, lo, std::max(lo, hi));
}

// The same time read on past the stretch's ends into the reference's own frames around it (inside
// its clip): what the reference's face did just before or after that phone. A cross-fade blends
// with the neighbour read so, as concatenative synthesis overlaps units with their own context:
// holding the neighbour's first or last frame instead blurred short phones into their neighbours
// (a bilabial's two frames half open), lowering the viseme contrast on every held-out fold.
double warped_in_context(const ReferenceFace& r, const FaceUnit& u, const FaceCandidate& c, double t) {
  const double rate = (c.end - c.start) / (u.end - u.start);
  const double lo = r.clip_first[static_cast<std::size_t>(c.clip)];
  const double hi = r.clip_end[static_cast<std::size_t>(c.clip)] - 1;
  return std::clamp(c.start + (t - u.start) * rate, lo, std::max(lo, hi));
}

}  // namespace

std::vector<FaceSource> face_sources(const ReferenceFace& r, const std::vector<FaceUnit>& units,
                                     const std::vector<FaceCandidate>& chosen, int frames, double crossfade_frames) {
  if (units.size() != chosen.size()) throw Error("face track: one stretch per unit is needed");
  std::vector<FaceSource> out(static_cast<std::size_t>(std::max(0, frames)));
  if (units.empty()) return out;
  std::size_t k = 0;
  for (int f = 0; f < frames; ++f) {
    const double t = f;
    while (k + 1 < units.size() && t >= units[k].end) ++k;
    FaceSource& s = out[static_cast<std::size_t>(f)];
    s.a = warped(r, units[k], chosen[k], t);
    // A cross-fade with the neighbour across the nearer join, when that join is a cut.
    const bool to_next = k + 1 < units.size() && units[k].end - t <= t - units[k].start;
    const std::size_t other = to_next ? k + 1 : (k > 0 ? k - 1 : k);
    if (other == k) continue;
    const FaceCandidate& before = chosen[std::min(k, other)];
    const FaceCandidate& after = chosen[std::max(k, other)];
    if (before.clip == after.clip && std::abs(before.end - after.start) < 0.5) continue;
    const double join = to_next ? units[k].end : units[k].start;
    const double half = std::min(
        {crossfade_frames, 0.5 * (units[k].end - units[k].start), 0.5 * (units[other].end - units[other].start)});
    const double d = std::abs(t - join);
    if (!(half > 0.0) || d >= half) continue;
    // Weight of the other stretch: 0.5 at the join, falling linearly to 0 at `half` from it.
    s.b = warped_in_context(r, units[other], chosen[other], t);
    s.w = 0.5 * (1.0 - d / half);
  }
  return out;
}

}  // namespace gmg
