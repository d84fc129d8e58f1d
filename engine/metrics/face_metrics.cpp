#include "engine/metrics/face_metrics.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/motion/body_parts.h"
#include "engine/motion/rotation.h"

namespace gmg {
namespace {

std::vector<double> smooth3(const std::vector<double>& v) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::size_t a = i > 0 ? i - 1 : i, b = std::min(v.size() - 1, i + 1);
    double sum = 0.0;
    for (std::size_t k = a; k <= b; ++k) sum += v[k];
    out[i] = sum / static_cast<double>(b - a + 1);
  }
  return out;
}

}  // namespace

std::vector<double> jaw_angles(const Motion& m) {
  std::vector<double> out;
  const int jaw = jaw_joint(m.skeleton);
  if (jaw < 0) return out;
  out.reserve(static_cast<std::size_t>(m.frame_count));
  for (int f = 0; f < m.frame_count; ++f) out.push_back(rotation_angle(m.rotation(f, jaw)));
  return out;
}

std::vector<double> frame_rms(const audio::Audio& sound, double fps, int frames) {
  if (!(fps > 0.0) || sound.sample_rate <= 0) throw Error("face metrics: no frame rate or sample rate");
  std::vector<double> out(static_cast<std::size_t>(std::max(0, frames)), 0.0);
  const auto n = static_cast<long long>(sound.samples.size());
  for (int f = 0; f < frames; ++f) {
    const long long a = std::max(0LL, std::llround((f - 0.5) / fps * sound.sample_rate));
    const long long b = std::min(n, std::llround((f + 0.5) / fps * sound.sample_rate));
    double sum = 0.0;
    for (long long i = a; i < b; ++i)
      sum +=
          static_cast<double>(sound.samples[static_cast<std::size_t>(i)]) * sound.samples[static_cast<std::size_t>(i)];
    out[static_cast<std::size_t>(f)] = b > a ? std::sqrt(sum / static_cast<double>(b - a)) : 0.0;
  }
  return out;
}

std::optional<double> jaw_energy_correlation(const std::vector<double>& jaw, const std::vector<double>& energy) {
  const std::size_t n = std::min(jaw.size(), energy.size());
  if (n < 3) return std::nullopt;
  const std::vector<double> a = smooth3({jaw.begin(), jaw.begin() + static_cast<std::ptrdiff_t>(n)});
  const std::vector<double> b = smooth3({energy.begin(), energy.begin() + static_cast<std::ptrdiff_t>(n)});
  double ma = 0.0, mb = 0.0;
  for (std::size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= static_cast<double>(n);
  mb /= static_cast<double>(n);
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  if (!(saa > 0.0) || !(sbb > 0.0)) return std::nullopt;
  return sab / std::sqrt(saa * sbb);
}

std::optional<double> viseme_contrast(const std::vector<double>& jaw, const std::vector<MouthSpan>& spans, double fps) {
  double open = 0.0, closed = 0.0;
  int n_open = 0, n_closed = 0;
  const int frames = static_cast<int>(jaw.size());
  for (const MouthSpan& s : spans) {
    const int a = std::max(0, static_cast<int>(std::ceil(s.start * fps)));
    const int b = std::min(frames, static_cast<int>(std::ceil(s.end * fps)));
    for (int f = a; f < b; ++f) {
      (s.open ? open : closed) += jaw[static_cast<std::size_t>(f)];
      ++(s.open ? n_open : n_closed);
    }
  }
  if (n_open == 0 || n_closed == 0 || !(closed > 0.0)) return std::nullopt;
  return (open / n_open) / (closed / n_closed);
}

double expressions_out_of_range(const std::vector<double>& expressions, const std::vector<double>& reference, int dims,
                                double margin) {
  if (dims <= 0 || reference.empty()) throw Error("face metrics: no reference expressions");
  const auto d = static_cast<std::size_t>(dims);
  std::vector<double> lo(d, INFINITY), hi(d, -INFINITY);
  for (std::size_t i = 0; i < reference.size(); ++i) {
    lo[i % d] = std::min(lo[i % d], reference[i]);
    hi[i % d] = std::max(hi[i % d], reference[i]);
  }
  const std::size_t frames = expressions.size() / d;
  if (frames == 0) return 0.0;
  std::size_t out = 0;
  for (std::size_t f = 0; f < frames; ++f)
    for (std::size_t k = 0; k < d; ++k) {
      const double e = expressions[f * d + k];
      if (!(e >= lo[k] - margin && e <= hi[k] + margin)) {
        ++out;
        break;
      }
    }
  return static_cast<double>(out) / static_cast<double>(frames);
}

}  // namespace gmg
