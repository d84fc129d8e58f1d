#include "engine/evaluate/evaluate_files.h"

#include <cmath>
#include <cstdio>

#include "audio/audio_file.h"
#include "audio/speech_check.h"
#include "audio/speech_energy.h"
#include "engine/core/error.h"
#include "engine/core/json.h"
#include "engine/core/strings.h"
#include "engine/evaluate/plot.h"
#include "engine/metrics/naturalness.h"
#include "engine/metrics/sync.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/up_axis.h"
#include "engine/pipeline/report_facts.h"
#include "graph/graph_io.h"

namespace gmg {

std::vector<Motion> read_reference_clips(const std::string& path, const std::string& skeleton, SmplxBody* out_body) {
  std::vector<Motion> clips;
  if (ends_with_ci(path, ".gmg")) {
    const MotionGraph g = graph_load(path);
    if (out_body) *out_body = g.body;
    for (const ClipInfo& c : g.clips)
      clips.push_back(motion_slice(g.motion, c.first_frame, c.first_frame + c.frame_count));
    g.check_unchanged();
  } else {
    clips.push_back(motion_read_y_up(path, skeleton));
    if (out_body && ends_with_ci(path, ".npz")) motion_read(path, skeleton, out_body);
  }
  return clips;
}

namespace {

// "x: lasts 3.0 s but the motion y lasts 5.0 s: ..." when speech and motion differ by more than
// kMaxEvaluateDurationMismatchS; "" otherwise.
std::string length_warning(const std::string& path, double sound_s, const std::string& motion_name, double motion_s) {
  if (std::abs(sound_s - motion_s) <= kMaxEvaluateDurationMismatchS) return "";
  char text[128];
  std::snprintf(text, sizeof text, ": lasts %.1f s but the motion ", sound_s);
  char tail[128];
  std::snprintf(tail, sizeof tail, " lasts %.1f s: the sync metrics compare them from their starts", motion_s);
  return path + text + motion_name + tail;
}

}  // namespace

audio::Audio read_evaluated_speech(const std::string& path, bool allow_silence, std::vector<std::string>& warnings) {
  audio::Audio sound = audio::read_audio(path, &warnings);
  if (!allow_silence) {
    const std::string problem = audio::speech_level_problem(sound.duration(), audio::energy_track(sound));
    if (!problem.empty()) throw Error(audio::speech_refusal(path, problem, warnings));
  }
  return sound;
}

EvaluateResult evaluate_files(const EvaluateInputs& in, const EvaluateOptions& options) {
  EvaluateLoaded l;
  // Every motion in Y-up, whatever its file's up axis, so feet, floors and heights are measured alike
  // (a graph's motion is Y-up already).
  l.generated = motion_read_y_up(in.generated, in.skeleton);
  l.generated_name = in.generated;
  if (ends_with_ci(in.generated, ".npz")) motion_read(in.generated, in.skeleton, &l.generated_body);
  if (!in.transcript.empty()) {
    l.mouth = mouth_spans(in.transcript);
    l.has_mouth = true;
  }
  if (!in.truth.empty()) {
    l.truth = motion_read_y_up(in.truth, in.skeleton);
    l.truth_name = in.truth;
  }
  if (!in.audio.empty()) {
    l.audio = read_evaluated_speech(in.audio, in.allow_silence, l.warnings);
    l.audio_name = in.audio;
  }
  for (const std::string& path : in.other_audio)
    l.other_audio.push_back(read_evaluated_speech(path, in.allow_silence, l.warnings));
  l.other_audio_names = in.other_audio;
  if (!in.reference.empty()) l.reference = read_reference_clips(in.reference, in.skeleton, &l.reference_body);
  l.reference_name = in.reference;
  if (!in.report.empty()) {
    l.report = read_json_file(in.report);
    l.report_name = in.report;
  }
  l.trim = in.trim;
  l.plot = in.plot;
  return evaluate_loaded(std::move(l), options);
}

EvaluateResult evaluate_loaded(EvaluateLoaded in, const EvaluateOptions& options) {
  EvaluateResult result;
  Motion& generated = in.generated;
  Motion& truth = in.truth;
  const bool has_truth = !in.truth_name.empty(), has_audio = !in.audio_name.empty(),
             has_report = !in.report_name.empty(), has_reference = !in.reference_name.empty();
  if (has_truth && in.trim && truth.frame_count != generated.frame_count) {
    Motion& longer = truth.frame_count > generated.frame_count ? truth : generated;
    const int keep = std::min(truth.frame_count, generated.frame_count);
    result.warnings.push_back("--trim: cut " + std::to_string(longer.frame_count - keep) + " frame(s) off the end of " +
                              (&longer == &truth ? in.truth_name : in.generated_name) + " (" +
                              std::to_string(longer.frame_count) + " -> " + std::to_string(keep) + ")");
    longer = motion_slice(longer, 0, keep);
  }
  for (const std::string& w : in.warnings) result.warnings.push_back(w);
  if (has_audio) {  // the other audio is mismatched by design: its length is no mistake
    const double generated_s = generated.fps > 0 ? generated.frame_count / generated.fps : 0.0;
    const std::string w = length_warning(in.audio_name, in.audio.duration(), in.generated_name, generated_s);
    if (!w.empty()) result.warnings.push_back(w);
  }
  ReportFacts facts;
  PlayedPaths paths;
  if (has_report) {
    facts = report_facts_of(in.report, generated.fps, in.report_name);
    paths = played_paths_of(in.report, in.report_name);
  }

  EvaluateData data;
  data.generated = &generated;
  data.generated_name = in.generated_name;
  if (has_truth) {
    data.truth = &truth;
    data.truth_name = in.truth_name;
  }
  if (has_reference)
    for (const Motion& m : in.reference) data.reference.push_back(&m);
  data.reference_name = in.reference_name;
  if (has_audio) data.audio = &in.audio;
  for (const audio::Audio& a : in.other_audio) data.other_audio.push_back(&a);
  if (has_report) data.paths = &paths;
  const nlohmann::ordered_json metrics = evaluate_motions(data, options);

  nlohmann::ordered_json inputs = {{"generated", in.generated_name}};
  if (has_truth) inputs["truth"] = in.truth_name;
  if (has_audio) inputs["audio"] = in.audio_name;
  if (!in.other_audio_names.empty()) inputs["other_audio"] = in.other_audio_names;
  if (has_reference) inputs["reference"] = in.reference_name;
  if (has_report) inputs["report"] = in.report_name;
  result.json["inputs"] = inputs;
  for (auto it = metrics.begin(); it != metrics.end(); ++it) result.json[it.key()] = it.value();
  if (nlohmann::ordered_json face = face_evaluation(generated, in); !face.is_null()) result.json["face"] = face;
  if (has_report) {
    result.json["failures"] = facts.totals["failures"];
    if (facts.totals.contains("fallbacks")) result.json["fallbacks"] = facts.totals["fallbacks"];
  }
  for (const std::string& w : result.warnings) result.json["notes"].push_back(w);

  if (!in.plot.empty()) {
    EvaluationPlot p;
    p.fps = generated.fps;
    p.title = in.generated_name;
    const double scale = length_unit_to_cm(generated.skeleton);
    p.generated_speed = mean_joint_speed(motion_forward_kinematics(generated) * scale, generated.fps);
    if (has_truth) p.truth_speed = mean_joint_speed(motion_forward_kinematics(truth) * scale, truth.fps);
    if (has_audio) {
      const SpeechTrack track = speech_track(in.audio);
      p.envelope = track.envelope;
      p.onsets_s = track.onset_times_s;
    }
    p.junctions_s = facts.junctions_s;
    plot_write(in.plot, p);
  }
  return result;
}

}  // namespace gmg
