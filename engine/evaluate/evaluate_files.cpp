#include "engine/evaluate/evaluate_files.h"

#include <cmath>
#include <cstdio>

#include "audio/audio_file.h"
#include "audio/speech_check.h"
#include "audio/speech_energy.h"
#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/evaluate/plot.h"
#include "engine/metrics/naturalness.h"
#include "engine/metrics/sync.h"
#include "engine/motion/motion_file.h"
#include "engine/pipeline/report_facts.h"
#include "graph/graph_io.h"

namespace gmg {
namespace {

std::vector<Motion> read_reference(const std::string& path, const std::string& skeleton) {
  std::vector<Motion> clips;
  if (ends_with_ci(path, ".gmg")) {
    const MotionGraph g = graph_load(path);
    for (const ClipInfo& c : g.clips)
      clips.push_back(motion_slice(g.motion, c.first_frame, c.first_frame + c.frame_count));
  } else {
    clips.push_back(motion_read(path, skeleton));
  }
  return clips;
}

// The speech of `path`, refused when it cannot be speech (unless allowed); a warning when it and
// the motion `motion_name` of `motion_s` seconds differ by more than a second (motion_s < 0: no
// such warning, for the mismatched speech of --other-audio).
audio::Audio read_speech(const std::string& path, bool allow_silence, const std::string& motion_name, double motion_s,
                         std::vector<std::string>& warnings) {
  audio::Audio sound = audio::read_audio(path, &warnings);
  if (!allow_silence) {
    const std::string problem = audio::speech_level_problem(sound.duration(), audio::energy_track(sound));
    if (!problem.empty()) throw Error(audio::speech_refusal(path, problem, warnings));
  }
  if (motion_s >= 0 && std::abs(sound.duration() - motion_s) > kMaxEvaluateDurationMismatchS) {
    char text[128];
    std::snprintf(text, sizeof text, ": lasts %.1f s but the motion ", sound.duration());
    char tail[128];
    std::snprintf(tail, sizeof tail, " lasts %.1f s: the sync metrics compare them from their starts", motion_s);
    warnings.push_back(path + text + motion_name + tail);
  }
  return sound;
}

}  // namespace

EvaluateResult evaluate_files(const EvaluateInputs& in, const EvaluateOptions& options) {
  EvaluateResult result;
  Motion generated = motion_read(in.generated, in.skeleton);
  Motion truth;
  if (!in.truth.empty()) {
    truth = motion_read(in.truth, in.skeleton);
    if (in.trim && truth.frame_count != generated.frame_count) {
      Motion& longer = truth.frame_count > generated.frame_count ? truth : generated;
      const int keep = std::min(truth.frame_count, generated.frame_count);
      result.warnings.push_back("--trim: cut " + std::to_string(longer.frame_count - keep) +
                                " frame(s) off the end of " + (&longer == &truth ? in.truth : in.generated) + " (" +
                                std::to_string(longer.frame_count) + " -> " + std::to_string(keep) + ")");
      longer = motion_slice(longer, 0, keep);
    }
  }
  const double generated_s = generated.fps > 0 ? generated.frame_count / generated.fps : 0.0;
  audio::Audio sound;
  if (!in.audio.empty()) sound = read_speech(in.audio, in.allow_silence, in.generated, generated_s, result.warnings);
  std::vector<audio::Audio> others;
  for (const std::string& path : in.other_audio)  // mismatched by design: its length is no mistake
    others.push_back(read_speech(path, in.allow_silence, in.generated, -1.0, result.warnings));
  const std::vector<Motion> reference =
      in.reference.empty() ? std::vector<Motion>() : read_reference(in.reference, in.skeleton);
  ReportFacts facts;
  if (!in.report.empty()) facts = read_report_facts(in.report, generated.fps);

  EvaluateData data;
  data.generated = &generated;
  data.generated_name = in.generated;
  if (!in.truth.empty()) {
    data.truth = &truth;
    data.truth_name = in.truth;
  }
  for (const Motion& m : reference) data.reference.push_back(&m);
  data.reference_name = in.reference;
  if (!in.audio.empty()) data.audio = &sound;
  for (const audio::Audio& a : others) data.other_audio.push_back(&a);
  if (!in.report.empty()) data.source_frames = &facts.source_frames;
  const nlohmann::ordered_json metrics = evaluate_motions(data, options);

  nlohmann::ordered_json inputs = {{"generated", in.generated}};
  if (!in.truth.empty()) inputs["truth"] = in.truth;
  if (!in.audio.empty()) inputs["audio"] = in.audio;
  if (!in.other_audio.empty()) inputs["other_audio"] = in.other_audio;
  if (!in.reference.empty()) inputs["reference"] = in.reference;
  if (!in.report.empty()) inputs["report"] = in.report;
  result.json["inputs"] = inputs;
  for (auto it = metrics.begin(); it != metrics.end(); ++it) result.json[it.key()] = it.value();
  if (!in.report.empty()) {
    result.json["failures"] = facts.totals["failures"];
    if (facts.totals.contains("fallbacks")) result.json["fallbacks"] = facts.totals["fallbacks"];
  }
  for (const std::string& w : result.warnings) result.json["notes"].push_back(w);

  if (!in.plot.empty()) {
    EvaluationPlot p;
    p.fps = generated.fps;
    p.title = in.generated;
    const double scale = length_unit_to_cm(generated.skeleton);
    p.generated_speed = mean_joint_speed(motion_forward_kinematics(generated) * scale, generated.fps);
    if (!in.truth.empty()) p.truth_speed = mean_joint_speed(motion_forward_kinematics(truth) * scale, truth.fps);
    if (!in.audio.empty()) {
      const SpeechTrack track = speech_track(sound);
      p.envelope = track.envelope;
      p.onsets_s = track.onset_times_s;
    }
    p.junctions_s = facts.junctions_s;
    plot_write(in.plot, p);
  }
  return result;
}

}  // namespace gmg
