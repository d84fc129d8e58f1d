// The objective evaluation of one generated motion (engine/metrics: metrics, naturalness, sync),
// in memory, as one JSON object. `gmg evaluate` (engine/evaluate/evaluate_files.h) reads the files.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "audio/wav.h"
#include "engine/metrics/lifelike.h"
#include "engine/metrics/metrics.h"
#include "engine/metrics/played_paths.h"
#include "engine/motion/body_parts.h"
#include "engine/motion/motion.h"

namespace gmg {

// Positions are compared in centimetres: a skeleton whose rest pose is under 5 units tall is
// taken to be in metres (BEAT2) and scaled by 100, others are taken as centimetres (GENEA, ZEGGS).
double length_unit_to_cm(const Skeleton& skeleton);

struct EvaluateData {
  const Motion* generated = nullptr;  // required
  std::string generated_name;
  const Motion* truth = nullptr;  // same skeleton, frame count and fps; null = skip
  std::string truth_name;
  std::vector<const Motion*> reference;  // the reference capture's clips (same skeleton); empty = none
  std::string reference_name;
  const audio::Audio* audio = nullptr;  // the speech; null = skip the sync metrics
  // Other speech (other clips or folds): the mismatched-speech control of every sync metric.
  std::vector<const audio::Audio*> other_audio;
  const PlayedPaths* paths = nullptr;  // what the output played (its report); null = skip the path metrics
};

struct EvaluateOptions {
  MetricParams metrics;
  LifelikeParams lifelike;
  int control_shifts = 8;  // circular shifts of the audio for the sync control
  double min_shift_s = 2.0;
};

// frames, fps, units; generated {jerk, acceleration, div}; bc and bc_control {aligned, shifted,
// shifted_mean, shifted_sd, lift}, speech_correlation (same form) when audio is given; syn,
// truth {...}, hellinger_speed_all / _wrists when the truth is given; naturalness {jerk_ratio,
// acc_ratio, root_speed_ratio against the truth, else the reference; jump_ratio, step_share
// against the reference's 99.9th percentile step, else the truth's; transitions_per_s when the
// paths are given}; energy_correlation and beat_consistency (engine/metrics/sync.h), each with the
// shifted and, with other_audio, the mismatched-speech control; lifelike (lifelike.h against the
// reference, else the truth: against, knee_share_ratio, knee_p90_deg, reference_knee_p90_deg,
// body_jerk_ratio, body_jerk_p99_ratio, still_longest_ratio, still_longest_s,
// reference_still_longest_s, foot_slide_ratio, foot_slide_share, reference_foot_slide_share; with
// the paths (played_paths.h) junctions_per_min, junction_gap_median_cm, stance_changes_per_min,
// max_plays_upper, max_plays_lower, back_jumps_upper, back_jumps_lower, and with a reference
// coverage; null where undefined); notes (what was skipped and why). Throws gmg::Error naming both files
// on a skeleton, length or frame-rate mismatch, and naming the motion when it is too short.
nlohmann::ordered_json evaluate_motions(const EvaluateData& data, const EvaluateOptions& options);

}  // namespace gmg
