#include "engine/metrics/evaluate.h"

#include <algorithm>

#include "audio/onset.h"
#include "audio/wav.h"
#include "engine/motion/bvh.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"

namespace gmg {

double length_unit_to_cm(const Skeleton& skeleton) {
  const Eigen::MatrixXd rest = motion_forward_kinematics(motion_rest(skeleton, 30.0, 1));
  double lo = 0.0, hi = 0.0;
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    lo = std::min(lo, rest(0, 3 * j + 1));
    hi = std::max(hi, rest(0, 3 * j + 1));
  }
  return hi - lo < 5.0 ? 100.0 : 1.0;
}

std::vector<int> wrist_joints(const Skeleton& skeleton) {
  std::vector<int> out;
  for (int j = 0; j < skeleton.joint_count(); ++j)
    if (ascii_lower(skeleton.joints[j].name).find("wrist") != std::string::npos) out.push_back(j);
  if (out.empty())
    for (int j = 0; j < skeleton.joint_count(); ++j) {
      const std::string n = ascii_lower(skeleton.joints[j].name);
      if (n.size() >= 4 && n.compare(n.size() - 4, 4, "hand") == 0) out.push_back(j);
    }
  return out;
}

nlohmann::ordered_json evaluate_motions(const Motion& generated, const std::string& generated_name, const Motion* truth,
                                        const std::string& truth_name, const std::vector<double>* audio_beats_s,
                                        const MetricParams& params) {
  nlohmann::ordered_json out;
  const double scale = length_unit_to_cm(generated.skeleton);
  const double fps = generated.fps;
  const Eigen::MatrixXd gen = motion_forward_kinematics(generated) * scale;
  out["frames"] = generated.frame_count;
  out["fps"] = fps;
  out["units"] = "cm";
  nlohmann::ordered_json notes = nlohmann::ordered_json::array();
  out["generated"] = {{"jerk_cm_s3", metric_jerk(gen, fps)}, {"acceleration_cm_s2", metric_acceleration(gen, fps)},
                      {"div", metric_div(gen, fps, params)}};
  if (audio_beats_s) {
    out["bc"] = metric_bc(gen, fps, *audio_beats_s, params);
  } else {
    notes.push_back("bc skipped: no --audio");
  }
  if (truth) {
    std::string why;
    if (!skeletons_match(generated.skeleton, truth->skeleton, &why))
      throw Error(generated_name + " and " + truth_name + " have different skeletons: " + why);
    if (generated.frame_count != truth->frame_count)
      throw Error(generated_name + " has " + std::to_string(generated.frame_count) + " frames but " + truth_name +
                  " has " + std::to_string(truth->frame_count) + ": metrics against the truth need equal lengths");
    if (std::abs(generated.fps - truth->fps) > 1e-6)
      throw Error(generated_name + " and " + truth_name + " have different frame rates");
    const Eigen::MatrixXd tru = motion_forward_kinematics(*truth) * scale;
    out["syn"] = metric_syn(gen, tru, fps);
    out["truth"] = {{"jerk_cm_s3", metric_jerk(tru, fps)}, {"acceleration_cm_s2", metric_acceleration(tru, fps)},
                    {"div", metric_div(tru, fps, params)}};
    if (audio_beats_s) out["truth"]["bc"] = metric_bc(tru, fps, *audio_beats_s, params);
    out["hellinger_speed_all"] = metric_hellinger_speed(gen, tru, fps, {}, params);
    const std::vector<int> wrists = wrist_joints(generated.skeleton);
    if (!wrists.empty()) {
      out["hellinger_speed_wrists"] = metric_hellinger_speed(gen, tru, fps, wrists, params);
    } else {
      notes.push_back("hellinger_speed_wrists skipped: no joint named *wrist* or *hand");
    }
  } else {
    notes.push_back("syn, hellinger and truth metrics skipped: no --truth");
  }
  out["notes"] = notes;
  return out;
}

nlohmann::ordered_json evaluate_files(const EvaluateInputs& in, const MetricParams& params) {
  const Motion generated = bvh_read(in.generated);
  Motion truth;
  if (!in.truth.empty()) truth = bvh_read(in.truth);
  std::vector<double> beats;
  if (!in.audio.empty()) beats = audio::detect_onsets(audio::read_wav(in.audio), audio::OnsetParams{}).onset_times();
  nlohmann::ordered_json out =
      evaluate_motions(generated, in.generated, in.truth.empty() ? nullptr : &truth, in.truth,
                       in.audio.empty() ? nullptr : &beats, params);
  nlohmann::ordered_json inputs = {{"generated", in.generated}};
  if (!in.truth.empty()) inputs["truth"] = in.truth;
  if (!in.audio.empty()) inputs["audio"] = in.audio;
  if (!in.report.empty()) {
    inputs["report"] = in.report;
    nlohmann::json rep;
    try {
      rep = nlohmann::json::parse(read_file_bytes(in.report));
    } catch (const nlohmann::json::parse_error& e) {
      throw Error(error_at_byte(in.report, static_cast<long long>(e.byte), "invalid JSON"));
    }
    if (!rep.contains("totals") || !rep["totals"].contains("failures"))
      throw Error(in.report + ": not a gmg reenactment report (no totals.failures)");
    out["failures"] = rep["totals"]["failures"];
    out["fallbacks"] = rep["totals"]["fallbacks"];
  }
  nlohmann::ordered_json full;
  full["inputs"] = inputs;
  for (auto it = out.begin(); it != out.end(); ++it) full[it.key()] = it.value();
  return full;
}

}  // namespace gmg
