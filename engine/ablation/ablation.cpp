#include "engine/ablation/ablation.h"

#include <cmath>
#include <map>
#include <random>

#include "audio/audio_file.h"
#include "engine/core/error.h"
#include "engine/metrics/behaviour.h"
#include "engine/metrics/evaluate.h"
#include "engine/metrics/naturalness.h"
#include "engine/metrics/sync.h"
#include "engine/motion/cleanup.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/up_axis.h"
#include "engine/pipeline/pipeline.h"
#include "search/initialisation.h"
#include "search/junction.h"
#include "text/transcript.h"

namespace gmg {

std::vector<TimeFold> time_folds(int frames, int k, int min_frames) {
  if (k < 2)
    throw Error("ablation: --folds must be at least 2 (one part is the test, the rest the reference), got " +
                std::to_string(k));
  std::vector<TimeFold> folds;
  auto bound = [&](int i) { return static_cast<int>(std::lround(static_cast<double>(i) * frames / k)); };
  for (int i = 0; i < k; ++i) {
    TimeFold f;
    f.test_first = bound(i);
    f.test_end = bound(i + 1);
    if (f.test_end - f.test_first < min_frames)
      throw Error("ablation: " + std::to_string(k) + " folds of " + std::to_string(frames) +
                  " frames leave a part of " + std::to_string(f.test_end - f.test_first) +
                  " frames; each part needs at least " + std::to_string(min_frames) + " (use fewer folds)");
    if (f.test_first > 0) f.reference.emplace_back(0, f.test_first);
    if (f.test_end < frames) f.reference.emplace_back(f.test_end, frames);
    folds.push_back(f);
  }
  return folds;
}

namespace {

// The whole recording in memory.
struct Recording {
  std::string name;
  Motion motion;
  audio::Audio sound;
  bool has_words = false;
  std::vector<text::Word> words;
};

audio::Audio audio_slice(const audio::Audio& a, double from_s, double to_s) {
  auto sample = [&](double t) {
    return std::min(a.samples.size(), static_cast<std::size_t>(std::max(0L, std::lround(t * a.sample_rate))));
  };
  audio::Audio out;
  out.sample_rate = a.sample_rate;
  out.samples.assign(a.samples.begin() + static_cast<std::ptrdiff_t>(sample(from_s)),
                     a.samples.begin() + static_cast<std::ptrdiff_t>(sample(to_s)));
  return out;
}

// Words wholly inside [from_s, to_s), with times relative to from_s.
std::vector<text::Word> words_slice(const std::vector<text::Word>& words, double from_s, double to_s) {
  std::vector<text::Word> out;
  for (const text::Word& w : words)
    if (w.start >= from_s && w.end <= to_s) out.push_back({w.start - from_s, w.end - from_s, w.text});
  return out;
}

// One fold, prepared once and shared by every setup and seed.
struct FoldData {
  TimeFold split;
  double fps = 30.0;
  double scale = 1.0;  // file units to centimetres
  audio::Audio test_audio;
  std::vector<text::Word> test_words;
  Eigen::MatrixXd truth_pos;
  NaturalnessReference reference;  // jerk, acceleration, root speed of the truth; step of the reference part
  std::vector<int> wrists, upper;
  LifelikeJoints lifelike_joints;
  LifelikeReference lifelike;      // of the reference part's pieces
  std::vector<double> mean_speed;  // per joint, of the reference part (the beat threshold's scale)
  double pose_variation = 0.0;     // of the reference part
  int reference_frames = 0;
  SyncControl control;  // mismatched: the other folds' speech
};

FoldData prepare_fold(const Recording& rec, const TimeFold& split, const AblationOptions& options) {
  const LifelikeParams& lp = options.lifelike;
  FoldData f;
  f.split = split;
  f.fps = rec.motion.fps;
  f.scale = length_unit_to_cm(rec.motion.skeleton);
  const double t0 = split.test_first / f.fps, t1 = split.test_end / f.fps;
  f.test_audio = audio_slice(rec.sound, t0, t1);
  if (rec.has_words) f.test_words = words_slice(rec.words, t0, t1);
  f.truth_pos = motion_forward_kinematics(motion_slice(rec.motion, split.test_first, split.test_end)) * f.scale;
  f.reference = naturalness_reference(f.truth_pos, f.fps);
  // The jump threshold comes from the reference part: longer than the truth, and what the graph
  // actually holds. Steps are taken inside each piece, never across the gap.
  std::vector<double> steps;
  for (const auto& [a, b] : split.reference) {
    const std::vector<double> s = frame_steps(motion_forward_kinematics(motion_slice(rec.motion, a, b)) * f.scale);
    steps.insert(steps.end(), s.begin(), s.end());
  }
  f.reference.step_p999 = percentile(steps, 99.9);
  // Mean joint speeds and pose variation of the reference part: its pieces joined (the one seam
  // between two pieces changes neither measurably).
  Eigen::MatrixXd ref_pos;
  f.lifelike_joints = lifelike_joints(rec.motion.skeleton);
  std::vector<LifelikeFacts> pieces;
  for (const auto& [a, b] : split.reference) {
    const Eigen::MatrixXd p = motion_forward_kinematics(motion_slice(rec.motion, a, b)) * f.scale;
    pieces.push_back(lifelike_facts(p, f.fps, f.lifelike_joints, lp));
    Eigen::MatrixXd joined(ref_pos.rows() + p.rows(), p.cols());
    joined << ref_pos, p;
    ref_pos.swap(joined);
    f.reference_frames += b - a;
  }
  f.wrists = wrist_joints(rec.motion.skeleton);
  f.upper = upper_body_joints(rec.motion.skeleton);
  f.lifelike = lifelike_reference(pieces, lp);
  f.mean_speed = joint_mean_speeds(ref_pos, f.fps);
  f.pose_variation = pose_variation(ref_pos);
  f.control = sync_control(f.test_audio, options.control_shifts, options.min_shift_s);
  return f;
}

// Every fold's speech is the other folds' mismatched speech.
void add_mismatched_speech(std::vector<FoldData>& folds) {
  for (std::size_t i = 0; i < folds.size(); ++i)
    for (std::size_t j = 0; j < folds.size(); ++j)
      if (j != i) folds[i].control.mismatched.push_back(folds[j].control.aligned);
}

// A graph of the fold's reference pieces, and the test speech analysed with the same parameters.
struct Prepared {
  MotionGraph graph;
  SpeechEvents test_events;
};

Prepared prepare_graph(const Recording& rec, const FoldData& fold, const GraphParams& gp,
                       const text::Lexicon& lexicon) {
  std::vector<ClipEvents> clips;
  for (const auto& [a, b] : fold.split.reference) {
    const double t0 = a / fold.fps, t1 = b / fold.fps;
    ClipEvents clip;
    clip.name = rec.name + " [" + std::to_string(a) + ", " + std::to_string(b) + ")";
    clip.motion = motion_slice(rec.motion, a, b);
    const std::vector<text::Word> words = words_slice(rec.words, t0, t1);
    const SpeechEvents ev = speech_events(audio_slice(rec.sound, t0, t1), rec.has_words ? &words : nullptr, clip.name,
                                          fold.fps, b - a, gp, lexicon);
    clip.onset_frames = ev.onset_frames;
    clip.keyword_frames = ev.keyword_frames;
    clip.speech = ev.features.values;
    clip.speech_dims = audio::SpeechFeatures::kDims;
    clips.push_back(std::move(clip));
  }
  Prepared p;
  p.graph = graph_build(std::move(clips), gp);
  p.test_events = speech_events(fold.test_audio, rec.has_words ? &fold.test_words : nullptr, "test part", fold.fps,
                                fold.split.test_end - fold.split.test_first, gp, lexicon);
  return p;
}

// The graph frames a plan reads, in output order.
std::vector<int> source_frames(const Plan& plan) {
  std::vector<int> out;
  for (const PlannedSegment& s : plan.segments) out.insert(out.end(), s.path.begin(), s.path.end());
  return out;
}

// The baselines' plans say where they continue and how far each junction jumps, as the planner's
// do (PlannedSegment continued, junction_gap), so their path metrics read alike.
void mark_junctions(Plan& plan, const MotionGraph& g) {
  JunctionCost junction(g);
  auto continues = [&](int f) { return f + 1 < g.frame_count() && !(g.node(f).kinds & kBreakNode); };
  for (std::size_t k = 1; k < plan.segments.size(); ++k) {
    PlannedSegment& seg = plan.segments[k];
    const int last = plan.segments[k - 1].path.back();
    seg.junction_from = continues(last) ? last + 1 : last;
    seg.continued = continues(last) && seg.path.front() == last + 1;
    seg.junction_gap = seg.continued ? 0.0 : junction.largest_joint_gap(seg.junction_from, seg.path.front());
  }
}

// The paths of a plan whose whole body follows it (the baselines).
PlayedPaths played_paths_of_plan(const Plan& plan, double scale) {
  PlayedPaths p;
  for (const PlannedSegment& s : plan.segments)
    p.upper.push_back({s.sub.start, s.sub.length, s.path, s.continued, s.transitions_inside, s.junction_gap * scale});
  return p;
}

// Frames f whose run (no break node before its end) reaches f + len - 1.
bool fits_in_run(const MotionGraph& g, int f, int len) {
  if (f + len > g.frame_count()) return false;
  for (int i = f; i < f + len - 1; ++i)
    if (g.node(i).kinds & kBreakNode) return false;
  return true;
}

// Contiguous baseline: one stretch of the reference as long as the test, from a random offset;
// when no piece is long enough, pieces follow each other from a random start (each change counts
// as a transition, as in any output).
Plan contiguous_plan(const MotionGraph& g, int length, std::mt19937_64& rng) {
  std::vector<int> starts;
  for (int f = 0; f < g.frame_count(); ++f)
    if (fits_in_run(g, f, length)) starts.push_back(f);
  Plan plan;
  if (!starts.empty()) {
    const int s = starts[random_below(rng, starts.size())];
    PlannedSegment seg;
    seg.sub = {0, length, Termination::Rhythm, ""};
    for (int i = 0; i < length; ++i) seg.path.push_back(s + i);
    seg.accepted = true;
    plan.segments.push_back(std::move(seg));
    return plan;
  }
  int f = static_cast<int>(random_below(rng, static_cast<std::uint64_t>(g.frame_count())));
  for (int covered = 0; covered < length;) {
    PlannedSegment seg;
    seg.sub.start = covered;
    while (covered < length) {
      seg.path.push_back(f);
      ++covered;
      const bool run_ends = (g.node(f).kinds & kBreakNode) != 0;
      f = (f + 1) % g.frame_count();
      if (run_ends) break;
    }
    seg.sub.length = static_cast<int>(seg.path.size());
    seg.accepted = true;
    plan.segments.push_back(std::move(seg));
  }
  return plan;
}

// Random-chunks baseline: chunks of `chunk` frames from random places in the reference.
Plan random_chunks_plan(const MotionGraph& g, int length, int chunk, std::mt19937_64& rng) {
  Plan plan;
  for (int covered = 0; covered < length;) {
    const int len = std::min(chunk, length - covered);
    std::vector<int> starts;
    for (int f = 0; f < g.frame_count(); ++f)
      if (fits_in_run(g, f, len)) starts.push_back(f);
    if (starts.empty())
      throw Error("ablation: the reference has no continuous run of " + std::to_string(len) + " frames");
    const int s = starts[random_below(rng, starts.size())];
    PlannedSegment seg;
    seg.sub = {covered, len, Termination::Rhythm, ""};
    for (int i = 0; i < len; ++i) seg.path.push_back(s + i);
    seg.accepted = true;
    plan.segments.push_back(std::move(seg));
    covered += len;
  }
  return plan;
}

SyncScores sync_scores(const Eigen::MatrixXd& pos, const FoldData& fold, const MetricParams& mp) {
  SyncScores s;
  const ControlledScore bc = bc_controlled(pos, fold.fps, fold.control, mp);
  s.bc = bc.aligned;
  s.bc_lift = bc.mismatched_lift();
  s.bc_shift_lift = bc.lift();
  s.bc_shifted_sd = bc.shifted_sd();
  const ControlledScore corr = speech_correlation_controlled(pos, fold.fps, fold.control);
  s.speech_corr = corr.aligned;
  s.speech_corr_lift = corr.mismatched_lift();
  s.speech_corr_shift_lift = corr.lift();
  s.speech_corr_shifted_sd = corr.shifted_sd();
  const ControlledScore energy = energy_correlation_controlled(pos, fold.fps, fold.upper, fold.control);
  s.energy_corr = energy.aligned;
  s.energy_corr_lift = energy.mismatched_lift();
  s.energy_corr_mismatched_sd = energy.mismatched_sd();
  const ControlledScore beat = bc_kinematic_controlled(pos, fold.fps, fold.upper, fold.mean_speed, fold.control);
  s.beat_bc = beat.aligned;
  s.beat_bc_lift = beat.mismatched_lift();
  s.beat_bc_mismatched_sd = beat.mismatched_sd();
  return s;
}

LifelikeMotion lifelike_scores(const Eigen::MatrixXd& pos, const FoldData& fold, const LifelikeParams& lp) {
  return lifelike_motion(lifelike_facts(pos, fold.fps, fold.lifelike_joints, lp), fold.lifelike, lp);
}

AblationScore score(const Motion& m, const Eigen::MatrixXd& pos, const Plan& plan, const PlayedPaths& paths,
                    const FoldData& fold, const AblationOptions& options) {
  const MetricParams& mp = options.metrics;
  AblationScore s;
  s.syn = metric_syn(pos, fold.truth_pos, fold.fps);
  s.sync = sync_scores(pos, fold, mp);
  s.lifelike = lifelike_scores(pos, fold, options.lifelike);
  s.paths = lifelike_paths(paths, fold.fps, m.duration(), options.lifelike);
  s.div = metric_div(pos, fold.fps, mp);
  s.hellinger = metric_hellinger_speed(pos, fold.truth_pos, fold.fps, {}, mp);
  if (!fold.wrists.empty()) s.hellinger_wrists = metric_hellinger_speed(pos, fold.truth_pos, fold.fps, fold.wrists, mp);
  const Naturalness n = naturalness(pos, fold.fps, fold.reference);
  s.jerk_ratio = n.jerk_ratio;
  s.acc_ratio = n.acc_ratio;
  s.root_speed_ratio = n.root_speed_ratio;
  s.jump_ratio = n.jump_ratio;
  s.step_share = n.step_share;
  const std::vector<int> sources = source_frames(plan);
  s.transitions_per_s = transitions_per_second(source_transitions(sources), m.duration());
  s.coverage = reference_reuse(sources, fold.reference_frames).coverage;
  s.failures = plan.failure_count();
  s.subsequences = static_cast<int>(plan.segments.size());
  return s;
}

// The configuration of a search setup (the baselines use the full one).
Config setup_config(AblationSetup setup, const Config& base) {
  Config c = base;
  switch (setup) {
    case AblationSetup::WeakDetection:
      c.graph.min_onset_strength = 0.0;
      break;
    case AblationSetup::WeakPruning:
      c.graph.l_pn = 1;
      break;
    case AblationSetup::WeakInitialization:
      c.search.init = InitMode::Random;
      break;
    case AblationSetup::NoFallback:
      c.search.fallbacks = false;
      break;
    default:
      break;
  }
  return c;
}

Recording read_recording(const AblationInputs& in, const Config& base) {
  Recording rec;
  rec.name = in.motion;
  rec.motion = motion_read(in.motion, in.skeleton);
  // In Y-up, as a graph's clips are (engine/motion/up_axis.h): the truth, the graph and the outputs
  // share the frame the metrics measure floors and heights in.
  motion_to_y_up(rec.motion, resolve_up_axis(rec.motion, base.graph.up));
  motion_lock_and_smooth(rec.motion, base.cleanup.lock_joints, base.cleanup.smooth_window, base.cleanup.smooth_order,
                         in.motion);
  rec.sound = audio::read_audio(in.audio);
  rec.has_words = !in.transcript.empty();
  if (rec.has_words) {
    rec.words = text::read_transcript(in.transcript);
    text::check_transcript_fits(rec.words, rec.sound.duration(), in.transcript);
  }
  return rec;
}

}  // namespace

AblationResult ablation_run(const AblationInputs& inputs, const AblationOptions& options, const Config& base) {
  config_validate(base);
  if (options.seeds.empty()) throw Error("ablation: no seeds");
  const Recording rec = read_recording(inputs, base);
  // Each test part must hold the sync control's shifts: 2 * min_shift + 1 s of audio.
  const int min_frames = static_cast<int>(std::ceil((2.0 * options.min_shift_s + 1.0) * rec.motion.fps));
  std::vector<TimeFold> folds;
  try {
    folds = time_folds(rec.motion.frame_count, options.folds, min_frames);
  } catch (const Error& e) {
    throw Error(inputs.motion + ": " + e.what());  // the recording that is too short
  }
  const text::Lexicon lexicon = lexicon_for(base.graph);
  constexpr AblationSetup kSetups[] = {
      AblationSetup::WeakDetection, AblationSetup::WeakPruning, AblationSetup::WeakInitialization,
      AblationSetup::NoFallback,    AblationSetup::Full,        AblationSetup::Contiguous,
      AblationSetup::RandomChunks};

  AblationResult result;
  result.folds = static_cast<int>(folds.size());
  result.seeds = static_cast<int>(options.seeds.size());
  result.control_shifts = options.control_shifts;
  result.hist_bins = options.metrics.hist_bins;
  result.hist_bin_width = options.metrics.hist_bin_width;
  for (AblationSetup s : kSetups) result.rows.push_back({s, {}});

  std::vector<FoldData> prepared_folds;
  prepared_folds.reserve(folds.size());
  for (const TimeFold& split : folds) prepared_folds.push_back(prepare_fold(rec, split, options));
  add_mismatched_speech(prepared_folds);
  for (const FoldData& fold : prepared_folds) {
    const TimeFold& split = fold.split;
    result.truth.push_back(
        {sync_scores(fold.truth_pos, fold, options.metrics), lifelike_scores(fold.truth_pos, fold, options.lifelike)});
    // Each setup's outputs of this fold, one per seed, for the distance between seeds.
    std::vector<std::vector<Eigen::MatrixXd>> outputs(result.rows.size());
    // Setups that agree on the graph parameters share one graph and one test analysis.
    std::map<std::pair<double, int>, Prepared> prepared;
    auto prepare = [&](const GraphParams& gp) -> const Prepared& {
      const auto key = std::make_pair(gp.min_onset_strength, gp.l_pn);
      auto it = prepared.find(key);
      if (it == prepared.end()) it = prepared.emplace(key, prepare_graph(rec, fold, gp, lexicon)).first;
      return it->second;
    };
    const int test_frames = split.test_end - split.test_first;
    for (std::uint64_t seed : options.seeds) {
      int full_chunk = 0;
      for (std::size_t r = 0; r < result.rows.size(); ++r) {
        AblationRow& row = result.rows[r];
        Config cfg = setup_config(row.setup, base);
        cfg.seed = seed;
        const Prepared& p = prepare(cfg.graph);
        std::mt19937_64 rng(seed);
        Plan plan;
        Motion motion;
        PlayedPaths paths;
        if (row.setup == AblationSetup::Contiguous || row.setup == AblationSetup::RandomChunks) {
          plan = row.setup == AblationSetup::Contiguous ? contiguous_plan(p.graph, test_frames, rng)
                                                        : random_chunks_plan(p.graph, test_frames, full_chunk, rng);
          motion = assemble_motion(p.graph, plan, assembly_params(cfg));
          mark_junctions(plan, p.graph);
          paths = played_paths_of_plan(plan, fold.scale);
        } else {
          Reenactment re = reenact_events(p.graph, p.test_events, cfg);
          // What `gmg evaluate --report` reads: the upper body's subsequences and the lower body's stretches.
          paths = played_paths_of(re.report,
                                  std::string("the ") + enum_name(kAblationSetupNames, row.setup) + " setup's report");
          plan = std::move(re.plan);
          motion = std::move(re.motion);
          if (row.setup == AblationSetup::Full)
            full_chunk = std::max(2, static_cast<int>(std::lround(static_cast<double>(test_frames) /
                                                                  static_cast<double>(plan.segments.size()))));
        }
        outputs[r].push_back(motion_forward_kinematics(motion) * fold.scale);
        row.scores.push_back(score(motion, outputs[r].back(), plan, paths, fold, options));
        row.scores.back().test_onsets = static_cast<int>(p.test_events.onset_frames.size());
      }
    }
    for (std::size_t r = 0; r < result.rows.size(); ++r) {
      double nearest = 0.0;
      for (std::size_t a = 0; a < outputs[r].size(); ++a)
        for (std::size_t b = a + 1; b < outputs[r].size(); ++b) {
          const double d = motion_distance(outputs[r][a], outputs[r][b]);
          nearest = a == 0 && b == 1 ? d : std::min(nearest, d);
        }
      const double ratio = fold.pose_variation > 0.0 ? nearest / fold.pose_variation : 0.0;
      const std::size_t first = result.rows[r].scores.size() - outputs[r].size();
      for (std::size_t k = first; k < result.rows[r].scores.size(); ++k) result.rows[r].scores[k].seed_distance = ratio;
    }
  }
  return result;
}

}  // namespace gmg
