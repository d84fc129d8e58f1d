#include "search/speech_match.h"

#include <algorithm>
#include <cmath>

#include "audio/speech_features.h"
#include "engine/core/error.h"
#include "graph/beats.h"
#include "graph/reference_facts.h"

namespace gmg {
namespace {

// Loudness, onset activity (audio/speech_features.h); further features weigh like onsets.
double dim_weight(int d) { return d == 0 ? 1.0 : 0.5; }

}  // namespace

SpeechMatch::SpeechMatch(const MotionGraph& g, const std::vector<float>& test, int test_frames, double rest_weight)
    : g_(g), test_(test), test_frames_(test_frames), rest_weight_(rest_weight) {
  active_ = g.has_speech() && !test.empty() && test_frames > 0;
  if (!active_) return;
  if (test.size() != static_cast<std::size_t>(test_frames) * static_cast<std::size_t>(g.speech_dims))
    throw Error("speech match: the test speech has " + std::to_string(test.size()) + " feature values for " +
                std::to_string(test_frames) + " frames of " + std::to_string(g.speech_dims) + " features");
  if (g.activity.size() != static_cast<std::size_t>(g.frame_count())) rest_weight_ = 0.0;
  pause_.resize(static_cast<std::size_t>(test_frames));
  for (int t = 0; t < test_frames; ++t) {
    const float loudness = test[static_cast<std::size_t>(t) * static_cast<std::size_t>(g.speech_dims)];
    pause_[static_cast<std::size_t>(t)] = audio::pause_weight(loudness);
  }
  runs_ = graph_runs(g);
  if (g.activity.size() == static_cast<std::size_t>(g.frame_count()))
    end_cost_ = g.beat_cost.size() == g.activity.size()
                    ? g.beat_cost
                    : Samples<float>(beat_end_costs(g.activity, runs_, g.motion.fps));
  // The scale: the mean feature distance of test and reference frames paired at random (4096
  // pairs spread over both, deterministic), so 1 is what a stretch unrelated to the speech costs,
  // whatever the recordings, and speech_weight compares with the junction cost (1 = a typical
  // transition) on every graph alike.
  constexpr int kPairs = 4096;
  double sum = 0.0;
  for (int i = 0; i < kPairs; ++i) {
    const int t = static_cast<int>(static_cast<long long>(i) * (test_frames - 1) / (kPairs - 1));
    const int f = static_cast<int>((static_cast<long long>(i) * 7919) % g.frame_count());
    sum += feature_cost(t, f);
  }
  scale_ = sum > 0.0 ? kPairs / sum : 1.0;
}

double SpeechMatch::feature_cost(int t, int f) const {
  const float* a = test_.data() + static_cast<std::size_t>(t) * static_cast<std::size_t>(g_.speech_dims);
  const float* b = g_.speech_at(f);
  double sum = 0.0;
  for (int d = 0; d < g_.speech_dims; ++d) {
    const double x = static_cast<double>(a[d]) - static_cast<double>(b[d]);
    sum += dim_weight(d) * x * x;
  }
  return sum;
}

double SpeechMatch::end_cost(int f) const {
  return active_ && !end_cost_.empty() ? end_cost_[static_cast<std::size_t>(f)] : 0.0;
}

double SpeechMatch::frame_cost(int t, int f) const {
  if (!active_) return 0.0;
  t = std::clamp(t, 0, test_frames_ - 1);
  double sum = scale_ * feature_cost(t, f);
  if (rest_weight_ > 0.0)
    sum += rest_weight_ * pause_[static_cast<std::size_t>(t)] * g_.activity[static_cast<std::size_t>(f)];
  return sum;
}

double SpeechMatch::path_cost(const std::vector<int>& path, int start, int length) const {
  if (!active_ || path.empty() || length < 1) return 0.0;
  const int n = static_cast<int>(path.size());
  double sum = 0.0;
  for (int i = 0; i < length; ++i) {
    const int k = length > 1 ? static_cast<int>(std::lround(static_cast<double>(i) * (n - 1) / (length - 1))) : 0;
    sum += frame_cost(start + i, path[static_cast<std::size_t>(k)]);
  }
  return sum / length;
}

void SpeechMatch::window_costs(int start, int window, const std::vector<int>& frames, std::vector<double>& out) const {
  out.assign(frames.size(), 0.0);
  if (!active_ || window < 1) return;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const int s = frames[k];
    const int last = runs_.last(s);
    double sum = 0.0;
    for (int i = 0; i < window; ++i) sum += frame_cost(start + i, std::min(s + i, last));
    out[k] = sum / window;
  }
}

}  // namespace gmg
