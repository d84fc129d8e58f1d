// `gmg ablation`: the paper's Table 2 (section 5.2) on one recording split in time, with naive
// baselines, naturalness columns and sync metrics with a control.
//
// The recording is cut into K time folds; each fold in turn is the test part (its audio, words and
// true motion) and the rest is the reference (one or two pieces, each a clip of one graph). Every
// setup is reenacted for every fold and seed and scored against the fold's truth:
//   weak_detection       min_onset_strength = 0 (graph and test speech)
//   weak_pruning         l_pn = 1
//   weak_initialization  init = random
//   no_fallback          fallbacks = false (failures counted)
//   full                 the configuration given
//   contiguous           a stretch of the reference as long as the test, from a random offset per
//                        seed: natural motion, no speech sync
//   random_chunks        reference chunks of the full system's mean path length (output frames
//                        per subsequence), joined with the full system's blending
// Columns (engine/metrics): syn, div; sync (bc, the onset-strength correlation, the energy
// correlation and the kinematic beat consistency, each with its lift over the other folds'
// speech, the first two also over shifted audio); naturalness ratios (jerk, acceleration and root
// speed to the truth's; jump ratio and share of steps above the reference part's 99.9th percentile
// step), Hellinger (all joints, wrists), transitions per second; lifelike (engine/metrics/lifelike.h
// against the fold's reference part: knee share, body jerk, still run, foot slide; played_paths.h
// from the plans: junctions, stance changes, plays, back-jumps, coverage); distance between seeds;
// failures. Mean and sample sd over folds x seeds (undefined values left out).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/config/config.h"
#include "engine/core/enum_names.h"
#include "engine/metrics/lifelike.h"
#include "engine/metrics/metrics.h"
#include "engine/metrics/played_paths.h"

namespace gmg {

enum class AblationSetup : std::uint8_t {
  WeakDetection,
  WeakPruning,
  WeakInitialization,
  NoFallback,
  Full,
  Contiguous,
  RandomChunks
};
inline constexpr EnumName<AblationSetup> kAblationSetupNames[] = {
    {AblationSetup::WeakDetection, "weak_detection"},
    {AblationSetup::WeakPruning, "weak_pruning"},
    {AblationSetup::WeakInitialization, "weak_initialization"},
    {AblationSetup::NoFallback, "no_fallback"},
    {AblationSetup::Full, "full"},
    {AblationSetup::Contiguous, "contiguous"},
    {AblationSetup::RandomChunks, "random_chunks"}};

// Frames [first, end) of one time fold's test part, and the reference pieces around it.
struct TimeFold {
  int test_first = 0, test_end = 0;
  std::vector<std::pair<int, int>> reference;  // [first, end) pieces, in time order, non-empty
};

// K folds of `frames`: test part i is [round(i N / K), round((i + 1) N / K)), so every frame is in
// exactly one test part. gmg::Error when K < 2 or a part would be shorter than min_frames.
std::vector<TimeFold> time_folds(int frames, int k, int min_frames);

struct AblationInputs {
  std::string motion, audio, transcript;  // one recording (BVH or SMPL-X .npz); transcript "" = none
  std::string skeleton{};                 // BVH skeleton template of an .npz motion (engine/motion/npz.h); "" = none
};

struct AblationOptions {
  int folds = 6;
  std::vector<std::uint64_t> seeds = {1, 2, 3, 4, 5};
  MetricParams metrics;  // Hellinger binning among others
  LifelikeParams lifelike;
  int control_shifts = 8;  // circular shifts of the test audio for the sync control
  double min_shift_s = 2.0;
};

// The sync scores of one motion: each aligned and its lift over mismatched speech (the other
// folds' speech) and over the circularly shifted test audio (engine/metrics/sync.h).
struct SyncScores {
  double bc = 0, bc_lift = 0, bc_shift_lift = 0, bc_shifted_sd = 0;
  double speech_corr = 0, speech_corr_lift = 0, speech_corr_shift_lift = 0, speech_corr_shifted_sd = 0;
  double energy_corr = 0, energy_corr_lift = 0, energy_corr_mismatched_sd = 0;
  double beat_bc = 0, beat_bc_lift = 0, beat_bc_mismatched_sd = 0;
};

// One setup on one fold with one seed.
struct AblationScore {
  SyncScores sync;
  LifelikeMotion lifelike;  // against the fold's reference part (NaN where undefined)
  LifelikePaths paths;      // the upper body's plan and, when layered, the lower body's stretches
  double syn = 0;
  double div = 0, hellinger = 0, hellinger_wrists = 0;
  double jerk_ratio = 0, acc_ratio = 0, root_speed_ratio = 0, jump_ratio = 0, step_share = 0;
  double transitions_per_s = 0;
  double coverage = 0;  // share of the fold's reference frames the upper body played
  // The smallest distance between this fold's outputs of two seeds (motion_distance), over the
  // reference part's pose_variation; the same for every seed of a fold (0 with one seed).
  double seed_distance = 0;
  int failures = 0;
  int subsequences = 0;  // pieces the output was planned in (the baselines: their chunks)
  int test_onsets = 0;   // onsets the detector found in the test speech
};

struct AblationRow {
  AblationSetup setup = AblationSetup::Full;
  std::vector<AblationScore> scores;  // fold-major: scores[fold * seeds + s]
};

// The truth's own scores per fold: what the recording itself allows a metric to see.
struct TruthSync {
  SyncScores sync;
  LifelikeMotion lifelike;  // against the fold's reference part
};

struct AblationResult {
  std::vector<AblationRow> rows;  // in AblationSetup order
  std::vector<TruthSync> truth;   // one per fold
  int folds = 0, seeds = 0, control_shifts = 0;
  HistogramBins hist_bins = HistogramBins::Overflow;
  double hist_bin_width = 1.0;
};

AblationResult ablation_run(const AblationInputs& inputs, const AblationOptions& options, const Config& base);

// Mean +- sd per column as a Markdown table (with notes on the binning and the truth's sync), and
// as CSV: a header row, then one row per setup with the columns setup, syn, syn_sd, bc, bc_sd,
// bc_lift, bc_lift_sd, div, div_sd, jerk_ratio, ..., failures, failures_sd, followed by
// step_share, bc_shifted_sd, speech_corr, speech_corr_lift, speech_corr_shifted_sd (each with _sd).
std::string ablation_markdown(const AblationResult& result);
std::string ablation_csv(const AblationResult& result);

}  // namespace gmg
