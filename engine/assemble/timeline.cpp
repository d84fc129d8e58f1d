#include "engine/assemble/timeline.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace gmg {

std::vector<SourceClock> source_timeline(const std::vector<PathPiece>& pieces, const std::vector<char>& continues) {
  std::vector<SourceClock> out;
  int run = -1;
  int previous_frame = -2;  // last path frame of the previous piece
  for (const PathPiece& piece : pieces) {
    const std::vector<int>& p = piece.path;
    if (p.empty() || piece.length < 1) throw Error("source_timeline: empty path or length");
    for (int f : p)
      if (f < 0 || f >= static_cast<int>(continues.size())) throw Error("source_timeline: path frame out of range");
    const int n = static_cast<int>(p.size());
    const double rate = piece.length > 1 ? static_cast<double>(n - 1) / (piece.length - 1) : 0.0;
    // run_first[k]: index in p of the first frame of the run holding p[k].
    std::vector<int> run_first(static_cast<std::size_t>(n));
    std::vector<int> run_id(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      const int before = k == 0 ? previous_frame : p[static_cast<std::size_t>(k - 1)];
      const bool natural = before >= 0 && p[static_cast<std::size_t>(k)] == before + 1 &&
                           continues[static_cast<std::size_t>(before)] != 0;
      if (!natural) ++run;
      run_first[static_cast<std::size_t>(k)] = natural && k > 0 ? run_first[static_cast<std::size_t>(k - 1)] : k;
      run_id[static_cast<std::size_t>(k)] = run;
    }
    for (int i = 0; i < piece.length; ++i) {
      const double x = std::min(static_cast<double>(n - 1), i * rate);
      const int a = std::min(n - 1, static_cast<int>(std::floor(x)));
      const int first = run_first[static_cast<std::size_t>(a)];
      SourceClock c;
      // Inside its run the path is consecutive frames, so source time is linear in x. Past the
      // run's last path frame (x between it and an unnatural jump) it reads on into the natural
      // successor, which exists unless that frame is a break.
      c.time = p[static_cast<std::size_t>(first)] + (x - first);
      const int base = static_cast<int>(std::floor(c.time));
      if (base >= static_cast<int>(continues.size()) || (c.time > base && !continues[static_cast<std::size_t>(base)]))
        c.time = base;
      c.rate = rate;
      c.run = run_id[static_cast<std::size_t>(a)];
      out.push_back(c);
    }
    previous_frame = p.back();
  }
  return out;
}

}  // namespace gmg
