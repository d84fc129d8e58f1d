#include "engine/motion/capture_runs.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"

namespace gmg {

CaptureRuns::CaptureRuns(int frames, std::vector<int> breaks) : frames_(frames), breaks_(std::move(breaks)) {
  if (frames < 0) throw Error("capture runs: a negative frame count");
  for (std::size_t i = 0; i < breaks_.size(); ++i)
    if (breaks_[i] < 0 || breaks_[i] >= frames || (i > 0 && breaks_[i] <= breaks_[i - 1]))
      throw Error("capture runs: break frame " + std::to_string(breaks_[i]) + " is out of order or outside the " +
                  std::to_string(frames) + " frames");
}

CaptureRuns::CaptureRuns(const std::vector<char>& continues) : frames_(static_cast<int>(continues.size())) {
  for (std::size_t f = 0; f < continues.size(); ++f)
    if (!continues[f]) breaks_.push_back(static_cast<int>(f));
}

bool CaptureRuns::continues(int f) const { return !std::binary_search(breaks_.begin(), breaks_.end(), f); }

int CaptureRuns::first(int f) const {
  const auto it = std::lower_bound(breaks_.begin(), breaks_.end(), f);
  return it == breaks_.begin() ? 0 : *(it - 1) + 1;
}

int CaptureRuns::last(int f) const {
  const auto it = std::lower_bound(breaks_.begin(), breaks_.end(), f);
  return it == breaks_.end() ? frames_ - 1 : *it;
}

bool CaptureRuns::readable(double t, int from) const {
  if (t < 0.0) return false;
  const int f = static_cast<int>(std::floor(t));
  if (f >= frames_ || first(f) != first(from)) return false;
  return t == f || (f + 1 < frames_ && continues(f));
}

bool CaptureRuns::velocity_partner(double t, double rate, double& out_time, double& out_sign) const {
  if (rate <= 0.0) return false;
  const int f = static_cast<int>(std::floor(t));
  if (readable(t - rate, f)) {
    out_time = t - rate;
    out_sign = 1.0;
    return true;
  }
  if (readable(t + rate, f)) {
    out_time = t + rate;
    out_sign = -1.0;
    return true;
  }
  return false;
}

}  // namespace gmg
