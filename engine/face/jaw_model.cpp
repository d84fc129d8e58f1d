#include "engine/face/jaw_model.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "engine/core/error.h"

namespace gmg {
namespace {

constexpr int kLag = 2;
// The ridge: small against the tens of thousands of frames' sums, large enough that a viseme the
// reference says once does not decide its weight alone.
constexpr double kRidge = 10.0;

int columns(int dims, bool with_visemes) { return 1 + (2 * kLag + 1) * dims + (with_visemes ? text::kVisemeCount : 0); }

// Row of frame f of a speech [first, end) (lags clamped to it).
void row_of(const float* z, int dims, int first, int end, int f, bool with_visemes, text::Viseme v, double* out) {
  int c = 0;
  out[c++] = 1.0;
  for (int lag = -kLag; lag <= kLag; ++lag) {
    const int g = std::clamp(f + lag, first, end - 1);
    for (int d = 0; d < dims; ++d) out[c++] = z[static_cast<std::size_t>(g) * static_cast<std::size_t>(dims) + d];
  }
  if (with_visemes)
    for (int k = 0; k < text::kVisemeCount; ++k) out[c++] = static_cast<int>(v) == k ? 1.0 : 0.0;
}

}  // namespace

std::vector<text::Viseme> frame_visemes(const std::vector<TimedViseme>& phones, int frames) {
  std::vector<text::Viseme> v(static_cast<std::size_t>(std::max(0, frames)), text::Viseme::Silence);
  for (const TimedViseme& p : phones) {
    const int a = std::max(0, static_cast<int>(std::ceil(p.start))),
              b = std::min(frames, static_cast<int>(std::ceil(p.end)));
    for (int f = a; f < b; ++f) v[static_cast<std::size_t>(f)] = p.viseme;
  }
  return v;
}

JawModel fit_jaw_model(const ReferenceFace& r, bool with_visemes) {
  if (!r.has_jaw()) throw Error("face track: no jaw to fit");
  JawModel m;
  m.with_visemes = with_visemes;
  const int n = columns(r.dims, with_visemes);
  std::vector<TimedViseme> timed;
  for (const FacePhone& p : r.phones) timed.push_back({p.start, p.end, text::viseme_of(p.symbol)});
  const std::vector<text::Viseme> visemes = frame_visemes(timed, r.frames);
  const int stride = std::max(1, r.frames / 50000);
  Eigen::MatrixXd xtx = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd xty = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd row(n);
  for (int f = 0; f < r.frames; f += stride) {
    const int clip = r.clip_of[static_cast<std::size_t>(f)];
    if (with_visemes && !r.has_phones[static_cast<std::size_t>(clip)]) continue;
    row_of(r.z.data(), r.dims, r.clip_first[static_cast<std::size_t>(clip)], r.clip_end[static_cast<std::size_t>(clip)],
           f, with_visemes, visemes[static_cast<std::size_t>(f)], row.data());
    xtx.selfadjointView<Eigen::Lower>().rankUpdate(row);
    xty += row * static_cast<double>(r.jaw[static_cast<std::size_t>(f)]);
  }
  Eigen::MatrixXd a = xtx.selfadjointView<Eigen::Lower>();
  a.diagonal().array() += kRidge;
  const Eigen::VectorXd w = a.ldlt().solve(xty);
  m.weights.assign(w.data(), w.data() + w.size());
  return m;
}

std::vector<double> predict_jaw(const JawModel& m, const std::vector<float>& z, int dims,
                                const std::vector<text::Viseme>& visemes) {
  const int frames = dims > 0 ? static_cast<int>(z.size() / static_cast<std::size_t>(dims)) : 0;
  const int n = columns(dims, m.with_visemes);
  if (static_cast<int>(m.weights.size()) != n) throw Error("face track: the jaw model does not fit these features");
  std::vector<double> out(static_cast<std::size_t>(frames));
  std::vector<double> row(static_cast<std::size_t>(n));
  for (int f = 0; f < frames; ++f) {
    const text::Viseme v = m.with_visemes && f < static_cast<int>(visemes.size()) ? visemes[static_cast<std::size_t>(f)]
                                                                                  : text::Viseme::Silence;
    row_of(z.data(), dims, 0, frames, f, m.with_visemes, v, row.data());
    double sum = 0.0;
    for (int c = 0; c < n; ++c) sum += row[static_cast<std::size_t>(c)] * m.weights[static_cast<std::size_t>(c)];
    out[static_cast<std::size_t>(f)] = sum;
  }
  return out;
}

}  // namespace gmg
