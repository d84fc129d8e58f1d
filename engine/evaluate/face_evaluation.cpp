// The face's part of `gmg evaluate` (engine/metrics/face_metrics.h over the files' contents).
#include <optional>

#include "engine/evaluate/evaluate_files.h"
#include "text/phones.h"

namespace gmg {

std::vector<MouthSpan> mouth_spans(const std::string& transcript) {
  std::vector<MouthSpan> out;
  for (const text::Phone& p : text::read_phones(transcript)) {
    const text::Viseme v = text::viseme_of(p.symbol);
    if (v == text::Viseme::OpenVowel || v == text::Viseme::Bilabial)
      out.push_back({p.start, p.end, v == text::Viseme::OpenVowel});
  }
  return out;
}

namespace {

nlohmann::ordered_json value_or_null(const std::optional<double>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

}  // namespace

nlohmann::ordered_json face_evaluation(const Motion& generated, const EvaluateLoaded& in) {
  const std::vector<double> jaw = jaw_angles(generated);
  const bool face = in.generated_body.has_face();
  if (jaw.empty() && !face) return nullptr;
  nlohmann::ordered_json j;
  if (!jaw.empty() && !in.audio_name.empty()) {
    j["jaw_energy_correlation"] =
        value_or_null(jaw_energy_correlation(jaw, frame_rms(in.audio, generated.fps, generated.frame_count)));
    if (!in.other_audio.empty()) {
      nlohmann::ordered_json mismatched = nlohmann::ordered_json::array();
      double sum = 0.0;
      int n = 0;
      for (const audio::Audio& other : in.other_audio) {
        const std::optional<double> c =
            jaw_energy_correlation(jaw, frame_rms(other, generated.fps, generated.frame_count));
        mismatched.push_back(value_or_null(c));
        if (c) sum += *c, ++n;
      }
      j["jaw_energy_mismatched"] = mismatched;
      j["jaw_energy_mismatched_mean"] = n > 0 ? nlohmann::ordered_json(sum / n) : nlohmann::ordered_json(nullptr);
    }
  }
  if (!jaw.empty() && in.has_mouth) j["viseme_contrast"] = value_or_null(viseme_contrast(jaw, in.mouth, generated.fps));
  if (face && in.reference_body.has_face() && in.reference_body.expression_dims == in.generated_body.expression_dims) {
    constexpr double kMargin = 0.05;
    j["expressions_out_of_range"] = expressions_out_of_range(
        in.generated_body.expressions, in.reference_body.expressions, in.generated_body.expression_dims, kMargin);
    j["expressions_margin"] = kMargin;
  }
  if (j.is_null()) return nullptr;
  return j;
}

}  // namespace gmg
