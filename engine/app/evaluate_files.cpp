#include "engine/app/evaluate_files.h"

#include "audio/wav.h"
#include "engine/app/plot.h"
#include "engine/core/error.h"
#include "engine/core/json.h"
#include "engine/core/strings.h"
#include "engine/metrics/naturalness.h"
#include "engine/metrics/sync.h"
#include "engine/motion/bvh.h"
#include "graph/graph_io.h"

namespace gmg {
namespace {

// What a reenactment report says about how the output was made.
struct ReportFacts {
  nlohmann::json totals;
  std::vector<int> source_frames;   // graph frames in output order
  std::vector<double> junctions_s;  // output times where the source jumps
};

ReportFacts read_report(const std::string& path, double fps) {
  const nlohmann::json rep = read_json_file(path);
  if (!rep.is_object() || !rep.contains("totals") || !rep["totals"].is_object() ||
      !rep["totals"].contains("failures") || !rep.contains("subsequences") || !rep["subsequences"].is_array())
    throw Error(path + ": not a gmg reenactment report (no totals.failures or subsequences)");
  ReportFacts f;
  f.totals = rep["totals"];
  int previous = -2;
  for (const nlohmann::json& s : rep["subsequences"]) {
    if (!s.is_object() || !s.contains("graph_ranges") || !s.contains("start_frame") || !s.contains("target_length") ||
        !s["graph_ranges"].is_array() || !s["start_frame"].is_number_integer() ||
        !s["target_length"].is_number_integer())
      throw Error(path + ": a subsequence lacks start_frame, target_length or graph_ranges");
    const int start = s["start_frame"].get<int>(), length = s["target_length"].get<int>();
    std::vector<int> frames;
    for (const nlohmann::json& r : s["graph_ranges"]) {
      if (!r.is_array() || r.size() != 2 || !r[0].is_number_integer() || !r[1].is_number_integer() ||
          r[1].get<long>() < r[0].get<long>() || r[1].get<long>() - r[0].get<long>() > 10000000)
        throw Error(path + ": a graph range is not [first, last]");
      for (int g = r[0].get<int>(); g <= r[1].get<int>(); ++g) frames.push_back(g);
    }
    // Output time of path index i: the path is resampled evenly onto the subsequence's frames.
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const int before = i == 0 ? previous : frames[i - 1];
      if (before != -2 && frames[i] != before + 1) {
        const double x = frames.size() > 1 ? static_cast<double>(i) * (length - 1) / (frames.size() - 1) : 0.0;
        f.junctions_s.push_back((start + x) / fps);
      }
    }
    if (!frames.empty()) previous = frames.back();
    f.source_frames.insert(f.source_frames.end(), frames.begin(), frames.end());
  }
  return f;
}

std::vector<Motion> read_reference(const std::string& path) {
  std::vector<Motion> clips;
  if (ends_with_ci(path, ".gmg")) {
    const MotionGraph g = graph_load(path);
    for (const ClipInfo& c : g.clips)
      clips.push_back(motion_slice(g.motion, c.first_frame, c.first_frame + c.frame_count));
  } else {
    clips.push_back(bvh_read(path));
  }
  return clips;
}

}  // namespace

EvaluateResult evaluate_files(const EvaluateInputs& in, const EvaluateOptions& options) {
  EvaluateResult result;
  Motion generated = bvh_read(in.generated);
  Motion truth;
  if (!in.truth.empty()) {
    truth = bvh_read(in.truth);
    if (in.trim && truth.frame_count != generated.frame_count) {
      Motion& longer = truth.frame_count > generated.frame_count ? truth : generated;
      const int keep = std::min(truth.frame_count, generated.frame_count);
      result.warnings.push_back("--trim: cut " + std::to_string(longer.frame_count - keep) +
                                " frame(s) off the end of " + (&longer == &truth ? in.truth : in.generated) + " (" +
                                std::to_string(longer.frame_count) + " -> " + std::to_string(keep) + ")");
      longer = motion_slice(longer, 0, keep);
    }
  }
  audio::Audio sound;
  if (!in.audio.empty()) sound = audio::read_wav(in.audio);
  const std::vector<Motion> reference = in.reference.empty() ? std::vector<Motion>() : read_reference(in.reference);
  ReportFacts facts;
  if (!in.report.empty()) facts = read_report(in.report, generated.fps);

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
  if (!in.report.empty()) data.source_frames = &facts.source_frames;
  const nlohmann::ordered_json metrics = evaluate_motions(data, options);

  nlohmann::ordered_json inputs = {{"generated", in.generated}};
  if (!in.truth.empty()) inputs["truth"] = in.truth;
  if (!in.audio.empty()) inputs["audio"] = in.audio;
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
