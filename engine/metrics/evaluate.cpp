#include "engine/metrics/evaluate.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/metrics/naturalness.h"
#include "engine/metrics/sync.h"

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

namespace {

nlohmann::ordered_json controlled_json(const ControlledScore& s, const std::vector<double>& shifts) {
  nlohmann::ordered_json j = {{"aligned", s.aligned},         {"shifted", s.shifted},
                              {"shifts_s", shifts},           {"shifted_mean", s.shifted_mean()},
                              {"shifted_sd", s.shifted_sd()}, {"lift", s.lift()}};
  if (!s.mismatched.empty()) {
    j["mismatched"] = s.mismatched;
    j["mismatched_mean"] = s.mismatched_mean();
    j["mismatched_lift"] = s.mismatched_lift();
  }
  return j;
}

void check_against(const Motion& generated, const std::string& gen_name, const Motion& other,
                   const std::string& other_name, bool same_length) {
  std::string why;
  if (!skeletons_match(generated.skeleton, other.skeleton, &why))
    throw Error(gen_name + " and " + other_name + " have different skeletons: " + why);
  if (same_length && generated.frame_count != other.frame_count)
    throw Error(gen_name + " has " + std::to_string(generated.frame_count) + " frames but " + other_name + " has " +
                std::to_string(other.frame_count) +
                ": metrics against the truth need equal lengths (evaluate --trim cuts the longer one)");
  if (std::abs(generated.fps - other.fps) > 1e-6)
    throw Error(gen_name + " and " + other_name + " have different frame rates");
}

// What the motion needs to be scored at all: jerk takes 4 frames.
void check_length(const Motion& m, const std::string& name) {
  if (m.frame_count < 4)
    throw Error(name + ": " + std::to_string(m.frame_count) + " frame" + (m.frame_count == 1 ? "" : "s") +
                ", the metrics need at least 4 (jerk is a third difference)");
}

// A value, or null where a metric is undefined (NaN): JSON has no NaN, and null reads back alike.
nlohmann::ordered_json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

// The lifelike metrics (lifelike.h against the reference's clips, else the truth; played_paths.h
// from the report's paths).
nlohmann::ordered_json lifelike_json(const EvaluateData& data, const Eigen::MatrixXd& gen, const LifelikeParams& params,
                                     nlohmann::ordered_json& notes) {
  const Motion& generated = *data.generated;
  const double scale = length_unit_to_cm(generated.skeleton);
  const LifelikeJoints joints = lifelike_joints(generated.skeleton);
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  std::vector<LifelikeFacts> reference;
  for (const Motion* clip : data.reference)
    reference.push_back(lifelike_facts(motion_forward_kinematics(*clip) * scale, clip->fps, joints, params));
  if (reference.empty() && data.truth)
    reference.push_back(
        lifelike_facts(motion_forward_kinematics(*data.truth) * scale, data.truth->fps, joints, params));
  if (!reference.empty()) {
    const LifelikeMotion m = lifelike_motion(lifelike_facts(gen, generated.fps, joints, params),
                                             lifelike_reference(reference, params), params);
    j["against"] = data.reference.empty() ? "truth" : "reference";
    if (joints.knees.empty()) {
      notes.push_back("knee metrics skipped: no joint named *knee* or *leg (not *upleg) with a child");
    } else {
      j["knee_share_ratio"] = number_or_null(m.knee_share_ratio);
      j["knee_p90_deg"] = number_or_null(m.knee_p90_deg);
      j["reference_knee_p90_deg"] = number_or_null(m.reference_knee_p90_deg);
    }
    j["body_jerk_ratio"] = number_or_null(m.body_jerk_ratio);
    j["body_jerk_p99_ratio"] = number_or_null(m.body_jerk_p99_ratio);
    j["still_longest_ratio"] = number_or_null(m.still_longest_ratio);
    j["still_longest_s"] = number_or_null(m.still_longest_s);
    j["reference_still_longest_s"] = number_or_null(m.reference_still_longest_s);
    if (joints.feet.empty()) {
      notes.push_back("foot slide skipped: no joint named *ankle* or *foot* (not toe or end)");
    } else {
      j["foot_slide_ratio"] = number_or_null(m.foot_slide_ratio);
      j["foot_slide_share"] = number_or_null(m.foot_slide_share);
      j["reference_foot_slide_share"] = number_or_null(m.reference_foot_slide_share);
    }
  } else {
    notes.push_back("lifelike motion metrics skipped: no --reference or --truth");
  }
  if (data.paths) {
    const LifelikePaths p = lifelike_paths(*data.paths, generated.fps, generated.duration(), params);
    j["junctions_per_min"] = p.junctions_per_min;
    j["junction_gap_median_cm"] = number_or_null(p.junction_gap_median_cm);
    j["stance_changes_per_min"] = p.stance_changes_per_min;
    j["max_plays_upper"] = p.max_plays_upper;
    j["max_plays_lower"] = p.max_plays_lower;
    j["back_jumps_upper"] = p.back_jumps_upper;
    j["back_jumps_lower"] = p.back_jumps_lower;
    if (!data.reference.empty()) {
      int frames = 0;
      for (const Motion* clip : data.reference) frames += clip->frame_count;
      j["coverage"] = reference_reuse(played_frames(data.paths->upper), frames).coverage;
    }
  } else {
    notes.push_back("junctions, plays and back-jumps skipped: no --report");
  }
  return j;
}

}  // namespace

nlohmann::ordered_json evaluate_motions(const EvaluateData& data, const EvaluateOptions& options) {
  if (!data.generated) throw Error("evaluate: no generated motion");
  const Motion& generated = *data.generated;
  check_length(generated, data.generated_name);
  const MetricParams& mp = options.metrics;
  nlohmann::ordered_json out;
  nlohmann::ordered_json notes = nlohmann::ordered_json::array();
  const double scale = length_unit_to_cm(generated.skeleton);
  const double fps = generated.fps;
  const Eigen::MatrixXd gen = motion_forward_kinematics(generated) * scale;
  out["frames"] = generated.frame_count;
  out["fps"] = fps;
  out["units"] = "cm";
  out["generated"] = {{"jerk_cm_s3", metric_jerk(gen, fps)},
                      {"acceleration_cm_s2", metric_acceleration(gen, fps)},
                      {"div", metric_div(gen, fps, mp)}};

  const std::vector<int> upper = upper_body_joints(generated.skeleton);
  Eigen::MatrixXd tru;
  if (data.truth) {
    check_against(generated, data.generated_name, *data.truth, data.truth_name, true);
    tru = motion_forward_kinematics(*data.truth) * scale;
  }
  if (data.audio) {
    if (data.audio->duration() >= 2.0 * options.min_shift_s + 1.0) {
      SyncControl control = sync_control(*data.audio, options.control_shifts, options.min_shift_s);
      for (const audio::Audio* other : data.other_audio) control.mismatched.push_back(speech_track(*other));
      const ControlledScore bc = bc_controlled(gen, fps, control, mp);
      out["bc"] = bc.aligned;
      out["bc_control"] = controlled_json(bc, control.shifts_s);
      out["speech_correlation"] = controlled_json(speech_correlation_controlled(gen, fps, control), control.shifts_s);
      // The beat threshold's scale: the reference's joint speeds, else the truth's, else its own.
      const std::vector<double> mean_speed =
          joint_mean_speeds(!data.reference.empty() ? motion_forward_kinematics(*data.reference.front()) * scale
                                                    : (data.truth ? tru : gen),
                            fps);
      out["energy_correlation"] =
          controlled_json(energy_correlation_controlled(gen, fps, upper, control), control.shifts_s);
      out["beat_consistency"] =
          controlled_json(bc_kinematic_controlled(gen, fps, upper, mean_speed, control), control.shifts_s);
      if (data.truth) {
        out["truth_sync"] = {
            {"bc", controlled_json(bc_controlled(tru, fps, control, mp), control.shifts_s)},
            {"speech_correlation", controlled_json(speech_correlation_controlled(tru, fps, control), control.shifts_s)},
            {"energy_correlation",
             controlled_json(energy_correlation_controlled(tru, fps, upper, control), control.shifts_s)},
            {"beat_consistency",
             controlled_json(bc_kinematic_controlled(tru, fps, upper, mean_speed, control), control.shifts_s)}};
      }
    } else {
      out["bc"] = metric_bc(gen, fps, speech_track(*data.audio).onset_times_s, mp);
      notes.push_back("sync control skipped: the audio is shorter than " +
                      format_number(2.0 * options.min_shift_s + 1.0) + " s");
    }
  } else {
    notes.push_back("bc and speech correlation skipped: no --audio");
  }

  if (data.truth) {
    out["syn"] = metric_syn(gen, tru, fps);
    out["truth"] = {{"jerk_cm_s3", metric_jerk(tru, fps)},
                    {"acceleration_cm_s2", metric_acceleration(tru, fps)},
                    {"div", metric_div(tru, fps, mp)}};
    out["hellinger_bins"] = enum_name(kHistogramBinsNames, mp.hist_bins);
    out["hellinger_bin_width"] = mp.hist_bin_width;
    out["hellinger_speed_all"] = metric_hellinger_speed(gen, tru, fps, {}, mp);
    const std::vector<int> wrists = wrist_joints(generated.skeleton);
    if (!wrists.empty()) {
      out["hellinger_speed_wrists"] = metric_hellinger_speed(gen, tru, fps, wrists, mp);
    } else {
      notes.push_back("hellinger_speed_wrists skipped: no joint named *wrist* or *hand");
    }
  } else {
    notes.push_back("syn, hellinger and truth metrics skipped: no --truth");
  }

  // Naturalness: ratios to the truth when there is one, else to the reference; the jump threshold
  // from the reference (longer, and what the output was made of) when there is one.
  std::vector<double> ref_steps;
  Eigen::MatrixXd ref_pos;
  for (const Motion* clip : data.reference) {
    check_against(generated, data.generated_name, *clip, data.reference_name, false);
    const Eigen::MatrixXd p = motion_forward_kinematics(*clip) * scale;
    const std::vector<double> s = frame_steps(p);
    ref_steps.insert(ref_steps.end(), s.begin(), s.end());
    if (ref_pos.size() == 0 || p.rows() > ref_pos.rows()) ref_pos = p;  // the longest clip for the ratios
  }
  if (data.truth || !ref_steps.empty()) {
    const bool ratios_from_truth = data.truth != nullptr;
    NaturalnessReference nr = naturalness_reference(ratios_from_truth ? tru : ref_pos, fps);
    if (!ref_steps.empty()) nr.step_p999 = percentile(ref_steps, 99.9);
    const Naturalness n = naturalness(gen, fps, nr);
    out["naturalness"] = {{"ratios_against", ratios_from_truth ? "truth" : "reference"},
                          {"steps_against", ref_steps.empty() ? "truth" : "reference"},
                          {"jerk_ratio", n.jerk_ratio},
                          {"acc_ratio", n.acc_ratio},
                          {"root_speed_ratio", n.root_speed_ratio},
                          {"jump_ratio", n.jump_ratio},
                          {"step_share", n.step_share},
                          {"step_p999_cm", nr.step_p999}};
  } else {
    notes.push_back("naturalness skipped: no --truth or --reference");
  }
  if (data.paths) {
    const int transitions = source_transitions(played_frames(data.paths->upper));
    if (out.contains("naturalness")) {
      out["naturalness"]["transitions_per_s"] = transitions_per_second(transitions, generated.duration());
    } else {
      out["naturalness"] = {{"transitions_per_s", transitions_per_second(transitions, generated.duration())}};
    }
  }
  out["lifelike"] = lifelike_json(data, gen, options.lifelike, notes);
  out["notes"] = notes;
  return out;
}

}  // namespace gmg
