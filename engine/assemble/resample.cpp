#include "engine/assemble/resample.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace gmg {

Motion resample_path(const Motion& source, const std::vector<int>& path, int length) {
  if (path.empty() || length < 1) throw Error("resample_path: empty path or length");
  Motion out = motion_rest(source.skeleton, source.fps, length);
  const int joints = source.joint_count();
  const int n = static_cast<int>(path.size());
  for (int i = 0; i < length; ++i) {
    const double x = length == 1 ? 0.0 : static_cast<double>(i) * (n - 1) / (length - 1);
    const int a = std::min(n - 1, static_cast<int>(std::floor(x)));
    const int b = std::min(n - 1, a + 1);
    const double t = x - a;
    for (int j = 0; j < joints; ++j) {
      out.rotations[out.index(i, j)] = slerp_shortest(source.rotation(path[a], j), source.rotation(path[b], j), t);
      out.translations[out.index(i, j)] =
          (1.0 - t) * source.translation(path[a], j) + t * source.translation(path[b], j);
    }
  }
  return out;
}

}  // namespace gmg
