#include "engine/app/ablation.h"

#include <cmath>
#include <map>
#include <cstdio>
#include <numeric>

#include "audio/onset.h"
#include "audio/wav.h"
#include "engine/motion/bvh.h"
#include "engine/motion/cleanup.h"
#include "engine/core/error.h"
#include "engine/metrics/metrics.h"
#include "engine/metrics/evaluate.h"
#include "engine/app/pipeline.h"

namespace gmg {

std::vector<AblationRow> ablation_run(const std::string& motion, const std::string& audio_path, const std::string& transcript,
                                      double reference_share, const std::vector<std::uint64_t>& seeds, const Config& base) {
  if (!(reference_share > 0.1 && reference_share < 0.9)) throw Error("ablation: the reference share must be in (0.1, 0.9)");
  Motion whole = bvh_read(motion);
  motion_lock_and_smooth(whole, base.cleanup.lock_joints, base.cleanup.smooth_window, base.cleanup.smooth_order, motion);
  const audio::Audio sound = audio::read_wav(audio_path);
  std::vector<text::Word> words;
  if (!transcript.empty()) words = text::read_transcript(transcript);
  const int split = static_cast<int>(std::lround(whole.frame_count * reference_share));
  const double split_s = split / whole.fps;
  const double test_s = (whole.frame_count - split) / whole.fps;
  const auto sample = [&](double t) { return std::min(sound.samples.size(), static_cast<std::size_t>(std::lround(t * sound.sample_rate))); };

  audio::Audio ref_audio{sound.sample_rate, {sound.samples.begin(), sound.samples.begin() + static_cast<std::ptrdiff_t>(sample(split_s))}};
  audio::Audio test_audio{sound.sample_rate, {sound.samples.begin() + static_cast<std::ptrdiff_t>(sample(split_s)),
                                              sound.samples.begin() + static_cast<std::ptrdiff_t>(sample(split_s + test_s))}};
  std::vector<text::Word> ref_words, test_words;
  for (const text::Word& w : words) {
    if (w.end <= split_s) ref_words.push_back(w);
    else if (w.start >= split_s && w.end <= split_s + test_s) test_words.push_back({w.start - split_s, w.end - split_s, w.text});
  }
  const Motion truth = motion_slice(whole, split, whole.frame_count);
  const std::vector<double> beats = audio::detect_onsets(test_audio, audio::OnsetParams{}).onset_times();
  const MetricParams metric_params;
  const double scale = length_unit_to_cm(whole.skeleton);
  const Eigen::MatrixXd truth_pos = motion_forward_kinematics(truth) * scale;

  struct Setup {
    const char* name;
    const char* set;
  };
  const Setup setups[] = {{"Weak Detection", "min_onset_strength=0"},
                          {"Weak Pruning", "l_pn=1"},
                          {"Weak Initialization", "init=random"},
                          {"No Term. Fallback", "fallbacks=false"},
                          {"Full", ""}};
  // The setups change at most min_onset_strength and l_pn of the graph parameters: graphs and
  // test events are built once per distinct pair and shared by the setups that agree on it.
  struct Prepared {
    MotionGraph graph;
    SpeechEvents test_events;
  };
  std::map<std::pair<double, int>, Prepared> prepared;
  const text::Lexicon lexicon = lexicon_for(base.graph);
  auto prepare = [&](const GraphParams& gp) -> const Prepared& {
    const auto key = std::make_pair(gp.min_onset_strength, gp.l_pn);
    auto it = prepared.find(key);
    if (it != prepared.end()) return it->second;
    ClipEvents clip;
    clip.name = motion + " [0, " + std::to_string(split) + ")";
    clip.motion = motion_slice(whole, 0, split);
    const SpeechEvents ref_ev = speech_events(ref_audio, transcript.empty() ? nullptr : &ref_words, "reference part",
                                              whole.fps, split, gp, lexicon);
    clip.onset_frames = ref_ev.onset_frames;
    clip.keyword_frames = ref_ev.keyword_frames;
    Prepared p{graph_build({clip}, gp),
               speech_events(test_audio, transcript.empty() ? nullptr : &test_words, "test part", whole.fps,
                             truth.frame_count, gp, lexicon)};
    return prepared.emplace(key, std::move(p)).first->second;
  };

  std::vector<AblationRow> rows;
  for (const Setup& s : setups) {
    Config cfg = base;
    if (*s.set) config_set_assignment(cfg, s.set);
    const Prepared& prep = prepare(cfg.graph);
    const MotionGraph& g = prep.graph;
    const SpeechEvents& test_ev = prep.test_events;
    AblationRow row;
    row.setup = s.name;
    for (std::uint64_t seed : seeds) {
      cfg.seed = seed;
      const Reenactment r = reenact_events(g, test_ev, cfg);
      const Eigen::MatrixXd pos = motion_forward_kinematics(r.motion) * scale;
      row.syn.push_back(metric_syn(pos, truth_pos, whole.fps));
      row.bc.push_back(metric_bc(pos, whole.fps, beats, metric_params));
      row.div.push_back(metric_div(pos, whole.fps, metric_params));
      row.failures.push_back(r.plan.failure_count());
    }
    rows.push_back(row);
  }
  return rows;
}

namespace {

std::pair<double, double> mean_sd(const std::vector<double>& v) {
  const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
  double ss = 0.0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return {mean, v.size() > 1 ? std::sqrt(ss / (v.size() - 1)) : 0.0};
}

std::vector<double> as_double(const std::vector<int>& v) { return {v.begin(), v.end()}; }

}  // namespace

std::string ablation_markdown(const std::vector<AblationRow>& rows) {
  std::string out = "| Setup | Syn (cm/s) ↓ | BC ↑ | Div ↑ | #Failure |\n| --- | --- | --- | --- | --- |\n";
  char buf[256];
  for (const AblationRow& r : rows) {
    const auto s = mean_sd(r.syn), b = mean_sd(r.bc), d = mean_sd(r.div), f = mean_sd(as_double(r.failures));
    std::snprintf(buf, sizeof buf, "| %s | %.4f ± %.4f | %.4f ± %.4f | %.4f ± %.4f | %.1f ± %.1f |\n", r.setup.c_str(), s.first,
                  s.second, b.first, b.second, d.first, d.second, f.first, f.second);
    out += buf;
  }
  return out;
}

std::string ablation_csv(const std::vector<AblationRow>& rows) {
  std::string out = "setup,syn_mean,syn_sd,bc_mean,bc_sd,div_mean,div_sd,failures_mean,failures_sd\n";
  char buf[256];
  for (const AblationRow& r : rows) {
    const auto s = mean_sd(r.syn), b = mean_sd(r.bc), d = mean_sd(r.div), f = mean_sd(as_double(r.failures));
    std::snprintf(buf, sizeof buf, "%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.3f,%.3f\n", r.setup.c_str(), s.first, s.second,
                  b.first, b.second, d.first, d.second, f.first, f.second);
    out += buf;
  }
  return out;
}

}  // namespace gmg
