#include "engine/face/units.h"

#include <algorithm>
#include <cmath>

namespace gmg {
namespace {

// Windows of unit_frames over [from, to); a remainder under half a window joins the last one.
void add_windows(double from, double to, int unit_frames, std::vector<FaceUnit>& out) {
  const double length = to - from;
  if (!(length > 0.0)) return;
  int count = std::max(1, static_cast<int>(std::floor(length / unit_frames)));
  if (length - count * unit_frames >= 0.5 * unit_frames) ++count;
  for (int i = 0; i < count; ++i) {
    FaceUnit u;
    u.start = from + i * static_cast<double>(unit_frames);
    u.end = i + 1 == count ? to : u.start + unit_frames;
    if (u.end > u.start) out.push_back(u);
  }
}

}  // namespace

std::vector<FaceUnit> face_units(const std::vector<text::Phone>* phones, double fps, int frames,
                                 const FaceParams& params) {
  std::vector<FaceUnit> out;
  const double total = frames;
  if (frames <= 0) return out;
  if (!phones || phones->empty()) {
    add_windows(0.0, total, params.unit_frames, out);
    return out;
  }
  const double silence_max = params.silence_unit_max_s * fps;
  double cursor = 0.0;
  const auto add_gap = [&](double to) {
    const double gap = to - cursor;
    if (gap <= 0.0) return;
    if (gap < 1.0 && !out.empty()) {  // a rounding gap between phones, not a pause
      out.back().end = to;
    } else if (gap <= silence_max) {
      FaceUnit u;
      u.start = cursor;
      u.end = to;
      u.phone = true;
      out.push_back(u);
    } else {
      add_windows(cursor, to, params.unit_frames, out);
    }
    cursor = to;
  };
  for (const text::Phone& p : *phones) {
    const double start = std::clamp(p.start * fps, cursor, total), end = std::clamp(p.end * fps, 0.0, total);
    if (!(end > start)) continue;
    add_gap(start);
    FaceUnit u;
    u.start = start;
    u.end = end;
    u.phone = true;
    u.symbol = p.symbol;
    out.push_back(u);
    cursor = end;
  }
  add_gap(total);
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!out[i].phone) continue;
    if (i > 0 && out[i - 1].phone) out[i].left = out[i - 1].symbol;
    if (i + 1 < out.size() && out[i + 1].phone) out[i].right = out[i + 1].symbol;
  }
  return out;
}

}  // namespace gmg
