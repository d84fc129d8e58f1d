#include "engine/pipeline/speech_report.h"

#include <algorithm>

#include "engine/core/csv.h"
#include "engine/core/error.h"
#include "engine/core/strings.h"

namespace gmg {

nlohmann::ordered_json speech_report_json(const SpeechFiles& files, double fps, const Config& config) {
  config_validate(config);
  if (!(fps > 0.0 && fps <= 1000.0)) throw Error("--fps must be in (0, 1000], got " + format_number(fps));
  const SpeechTimes times = speech_times(files, config.graph);
  const SpeechEvents ev = speech_events_on_grid(times, fps, -1, lexicon_for(config.graph));
  nlohmann::ordered_json out;
  out["audio"] = files.audio;
  out["transcript"] =
      files.transcript.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(files.transcript);
  out["duration_s"] = times.duration_s;
  out["fps"] = fps;
  out["frames"] = ev.total_frames;
  nlohmann::ordered_json onsets = nlohmann::ordered_json::array();
  const std::vector<double> t = times.onsets.onset_times();
  for (std::size_t i = 0; i < t.size(); ++i) {
    const long frame = std::lround(t[i] * fps);
    if (frame < 0 || frame >= ev.total_frames) continue;
    onsets.push_back({{"time_s", t[i]}, {"frame", frame}, {"strength", times.onsets.peak_strengths[i]}});
  }
  out["onsets"] = onsets;
  nlohmann::ordered_json keywords = nlohmann::ordered_json::array();
  if (times.has_words)
    for (const text::KeywordEvent& k : text::detect_keywords(times.words, lexicon_for(config.graph))) {
      const long frame = std::lround(k.time * fps);
      if (frame >= 0 && frame < ev.total_frames)
        keywords.push_back({{"time_s", k.time}, {"frame", frame}, {"keyword", k.keyword}});
    }
  out["keywords"] = keywords;
  // The phones the face track plays (engine/face), from the transcript's phones tier.
  nlohmann::ordered_json phones = nlohmann::ordered_json::array();
  for (const text::Phone& p : times.phones)
    phones.push_back({{"start_s", p.start},
                      {"end_s", p.end},
                      {"phone", p.symbol},
                      {"viseme", std::string(enum_name(text::kVisemeNames, text::viseme_of(p.symbol)))}});
  out["phones"] = phones;
  std::vector<float> loud, activity, pause;
  for (int f = 0; f < ev.features.frames(); ++f) {
    const float l = ev.features.values[static_cast<std::size_t>(f) * audio::SpeechFeatures::kDims];
    loud.push_back(l);
    activity.push_back(ev.features.values[static_cast<std::size_t>(f) * audio::SpeechFeatures::kDims + 1]);
    pause.push_back(audio::pause_weight(l));
  }
  out["features"] = {{"loudness", loud}, {"onset_activity", activity}, {"pause", pause}};
  return out;
}

std::string speech_report_csv(const nlohmann::ordered_json& report) {
  std::string out = csv_line({"kind", "time_s", "frame", "strength", "keyword"});
  for (const auto& o : report["onsets"])
    out += csv_line({"onset", format_number(o["time_s"].get<double>()), std::to_string(o["frame"].get<long>()),
                     format_number(o["strength"].get<double>()), ""});
  for (const auto& k : report["keywords"])
    out += csv_line({"keyword", format_number(k["time_s"].get<double>()), std::to_string(k["frame"].get<long>()), "",
                     k["keyword"].get<std::string>()});
  return out;
}

}  // namespace gmg
