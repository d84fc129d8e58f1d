#include "engine/face/candidates.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "text/phones.h"

namespace gmg {
namespace {

// How much stretches are looked at, at most, for a window unit: they start every third frame (a
// face changes little in 100 ms, and the scan is most of the audio-only track's time), every few
// frames in a longer reference; each is compared over the window's own frames.
constexpr int kMaxWindowStarts = 20000;
constexpr int kWindowStep = 3;
// A phone unit's reference phones of other symbols of the same viseme join its own while it has
// fewer than this many.
constexpr std::size_t kMinSameSymbol = 4;

// The visemes of a phone and of its neighbours.
struct PhoneVisemes {
  text::Viseme symbol, left, right;
};

template <typename Phone>
PhoneVisemes visemes_of(const Phone& p) {
  return {text::viseme_of(p.symbol), text::viseme_of(p.left), text::viseme_of(p.right)};
}

class TargetCost {
 public:
  TargetCost(const ReferenceFace& r, const FaceTarget& t, const FaceParams& p) : r_(r), t_(t), p_(p) {
    w_.assign(static_cast<std::size_t>(r.dims), p.spectrum_weight);
    if (!w_.empty()) w_[0] = 1.0;  // loudness
    double sum = 0.0;
    for (double w : w_) sum += w;
    for (double& w : w_) w = sum > 0.0 ? w / sum : 0.0;
  }

  // The sound and jaw terms of playing reference [c.start, c.end) warped onto output [u.start,
  // u.end): over the unit's frames (and `context` frames either side), each read at the reference
  // frame nearest its warped time, within the candidate's clip.
  double speech_cost(const FaceUnit& u, const FaceCandidate& c, int context) const {
    int a = static_cast<int>(std::ceil(u.start)) - context, b = static_cast<int>(std::ceil(u.end)) + context;
    if (b <= a) {  // shorter than a frame: its nearest frame
      a = static_cast<int>(std::lround(0.5 * (u.start + u.end)));
      b = a + 1;
    }
    a = std::max(a, 0);
    b = std::min(b, t_.frames);
    if (b <= a) return 0.0;
    const double rate = (c.end - c.start) / (u.end - u.start);
    const int lo = r_.clip_first[static_cast<std::size_t>(c.clip)],
              hi = r_.clip_end[static_cast<std::size_t>(c.clip)] - 1;
    const int dims = r_.dims;
    double sound = 0.0, jaw = 0.0;
    for (int f = a; f < b; ++f) {
      const int rf = std::clamp(static_cast<int>(std::lround(c.start + (f - u.start) * rate)), lo, hi);
      const float* zr = &r_.z[static_cast<std::size_t>(rf) * static_cast<std::size_t>(dims)];
      const float* zt = &t_.z[static_cast<std::size_t>(f) * static_cast<std::size_t>(dims)];
      double s = 0.0;
      for (int d = 0; d < dims; ++d) s += w_[static_cast<std::size_t>(d)] * (zr[d] - zt[d]) * (zr[d] - zt[d]);
      sound += s;
      if (!t_.jaw.empty()) jaw += std::abs(r_.jaw[static_cast<std::size_t>(rf)] - t_.jaw[static_cast<std::size_t>(f)]);
    }
    const double n = b - a;
    return p_.audio_weight * std::sqrt(sound / n) + (t_.jaw.empty() ? 0.0 : p_.jaw_weight * jaw / n / r_.jaw_sd);
  }

  // A phone unit's own terms: the phone, its neighbours and its length (the visemes looked up once
  // per phone: text::phone_difference's, without its search of the viseme table).
  double phone_cost(const FaceUnit& u, const PhoneVisemes& uv, const FacePhone& ref, const PhoneVisemes& rv) const {
    const auto differ = [](const std::string& a, text::Viseme va, const std::string& b, text::Viseme vb) {
      return a == b ? 0 : va == vb ? 1 : 2;
    };
    const double length = (ref.end - ref.start) / (u.end - u.start);
    return p_.phone_weight * differ(u.symbol, uv.symbol, ref.symbol, rv.symbol) +
           p_.context_weight * 0.5 *
               (differ(u.left, uv.left, ref.left, rv.left) + differ(u.right, uv.right, ref.right, rv.right)) +
           p_.duration_weight * std::abs(std::log(length));
  }

 private:
  const ReferenceFace& r_;
  const FaceTarget& t_;
  const FaceParams& p_;
  std::vector<double> w_;  // each feature's weight, summing to 1
};

void keep_best(std::vector<FaceCandidate>& c, int k) {
  const auto cheaper = [](const FaceCandidate& a, const FaceCandidate& b) {
    return a.cost < b.cost || (a.cost == b.cost && a.start < b.start);
  };
  if (static_cast<int>(c.size()) > k) {
    std::nth_element(c.begin(), c.begin() + k, c.end(), cheaper);
    c.resize(static_cast<std::size_t>(k));
  }
  std::sort(c.begin(), c.end(), cheaper);
}

// `scratch` holds every stretch looked at (reused from unit to unit: growing a new list for each
// window was half the audio-only track's time); the best params.candidates are returned.
std::vector<FaceCandidate> window_candidates(const ReferenceFace& r, const FaceUnit& u, const TargetCost& cost,
                                             const FaceParams& p, std::vector<FaceCandidate>& scratch) {
  const double length = u.end - u.start;
  const int whole = std::max(1, static_cast<int>(std::ceil(length)));
  const int stride = std::max(kWindowStep, r.frames / kMaxWindowStarts);
  std::vector<FaceCandidate>& out = scratch;
  out.clear();
  out.reserve(static_cast<std::size_t>(r.frames / stride + static_cast<int>(r.clip_first.size())));
  for (std::size_t c = 0; c < r.clip_first.size(); ++c) {
    const int first = r.clip_first[c], last = r.clip_end[c] - whole;
    for (int s = first; s <= last; s += stride) {
      FaceCandidate fc{static_cast<double>(s), s + length, static_cast<int>(c), 0.0};
      fc.cost = cost.speech_cost(u, fc, 0);
      out.push_back(fc);
    }
  }
  keep_best(out, p.candidates);
  return {out.begin(), out.end()};
}

}  // namespace

std::vector<std::vector<FaceCandidate>> face_candidates(const ReferenceFace& r, const std::vector<FaceUnit>& units,
                                                        const FaceTarget& target, const FaceParams& params) {
  const TargetCost cost(r, target, params);
  std::map<std::string, std::vector<int>> by_symbol;
  std::vector<std::vector<int>> by_viseme(text::kVisemeCount);
  std::vector<PhoneVisemes> ref_visemes;
  ref_visemes.reserve(r.phones.size());
  for (std::size_t i = 0; i < r.phones.size(); ++i) {
    ref_visemes.push_back(visemes_of(r.phones[i]));
    by_symbol[r.phones[i].symbol].push_back(static_cast<int>(i));
    by_viseme[static_cast<std::size_t>(ref_visemes.back().symbol)].push_back(static_cast<int>(i));
  }
  std::vector<std::vector<FaceCandidate>> out;
  out.reserve(units.size());
  std::vector<FaceCandidate> scratch;
  for (const FaceUnit& u : units) {
    std::vector<int> pool;
    const PhoneVisemes uv = visemes_of(u);
    if (u.phone) {
      const auto it = by_symbol.find(u.symbol);
      if (it != by_symbol.end()) pool = it->second;
      if (pool.size() < kMinSameSymbol)
        for (int i : by_viseme[static_cast<std::size_t>(uv.symbol)])
          if (r.phones[static_cast<std::size_t>(i)].symbol != u.symbol) pool.push_back(i);
    }
    if (pool.empty()) {
      out.push_back(window_candidates(r, u, cost, params, scratch));
      continue;
    }
    std::vector<FaceCandidate> c;
    c.reserve(pool.size());
    for (int i : pool) {
      const FacePhone& ph = r.phones[static_cast<std::size_t>(i)];
      FaceCandidate fc{ph.start, ph.end, ph.clip, 0.0};
      fc.cost = cost.phone_cost(u, uv, ph, ref_visemes[static_cast<std::size_t>(i)]) + cost.speech_cost(u, fc, 0);
      c.push_back(fc);
    }
    keep_best(c, params.candidates);
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace gmg
