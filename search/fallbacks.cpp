#include "search/fallbacks.h"

namespace gmg {

BeamRequest fallback_rhythm_request(const BeamRequest& request) {
  BeamRequest r = request;
  r.kind = Termination::Rhythm;
  r.keyword.clear();
  return r;
}

BeamRequest fallback_ignore_stops_request(const BeamRequest& request, const std::vector<int>& keys, int frame_count,
                                          int round, int rounds, std::mt19937_64& rng) {
  BeamRequest r = request;
  const double share = static_cast<double>(round) / (rounds + 1);
  r.ignore_stop.assign(static_cast<std::size_t>(frame_count), 0);
  // A uniform double in [0, 1) from the top 53 bits: the same on every standard library.
  for (int f : keys)
    if (static_cast<double>(rng() >> 11) * 0x1.0p-53 < share) r.ignore_stop[static_cast<std::size_t>(f)] = 1;
  return r;
}

}  // namespace gmg
