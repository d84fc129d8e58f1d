#include "engine/pipeline/pipeline.h"

#include "engine/pipeline/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <random>

#include "audio/audio_file.h"
#include "audio/onset.h"
#include "audio/speech_check.h"
#include "engine/assemble/blend.h"
#include "engine/assemble/resample.h"
#include "engine/assemble/transitions.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/limits.h"
#include "engine/core/parallel.h"
#include "engine/core/strings.h"
#include "engine/metrics/evaluate.h"
#include "engine/motion/cleanup.h"
#include "engine/motion/motion_file.h"
#include "search/segmentation.h"

namespace gmg {

text::Lexicon lexicon_for(const GraphParams& params) {
  return params.keywords.empty() ? text::default_lexicon() : text::load_lexicon(params.keywords);
}

namespace {

SpeechTimes times_of(audio::OnsetAnalysis onsets, audio::EnergyTrack energy, double duration_s,
                     const std::vector<text::Word>* words, const std::string& name) {
  SpeechTimes t;
  t.duration_s = duration_s;
  t.onsets = std::move(onsets);
  t.energy = std::move(energy);
  t.name = name;
  if (words) {
    text::check_transcript_fits(*words, duration_s, name);
    t.words = *words;
    t.has_words = true;
  }
  return t;
}

audio::OnsetParams onset_params_of(const GraphParams& params) {
  audio::OnsetParams p;
  p.min_onset_strength = params.min_onset_strength;
  return p;
}

}  // namespace

SpeechEvents speech_events_on_grid(const SpeechTimes& times, double fps, int frame_count,
                                   const text::Lexicon& lexicon) {
  SpeechEvents ev;
  ev.duration_s = times.duration_s;
  if (frame_count < 0 && !(ev.duration_s * fps <= limits::kMaxFrames))
    throw Error(times.name + ": " + format_number(ev.duration_s) + " s of speech at " + format_number(fps) +
                " fps is more than the " + std::to_string(limits::kMaxFrames) + " frames gmg makes");
  ev.total_frames = frame_count >= 0 ? frame_count : static_cast<int>(std::lround(ev.duration_s * fps));
  if (ev.total_frames < 1) throw Error(times.name + ": audio is shorter than one motion frame");
  ev.onset_frames = audio::onset_motion_frames(times.onsets, fps, ev.total_frames);
  ev.features = audio::speech_features(times.energy, times.onsets.envelope, fps, ev.total_frames);
  ev.warnings = times.warnings;
  if (times.has_words) {
    ev.words = static_cast<int>(times.words.size());
    for (const text::KeywordFrame& k :
         text::keyword_frames(text::detect_keywords(times.words, lexicon), fps, ev.total_frames))
      ev.keyword_frames.emplace_back(k.frame, k.keyword);
  }
  return ev;
}

SpeechEvents speech_events(const audio::Audio& sound, const std::vector<text::Word>* words, const std::string& name,
                           double fps, int frame_count, const GraphParams& params, const text::Lexicon& lexicon) {
  const SpeechTimes t = times_of(audio::detect_onsets(sound, onset_params_of(params)), audio::energy_track(sound),
                                 sound.duration(), words, name);
  return speech_events_on_grid(t, fps, frame_count, lexicon);
}

SpeechTimes speech_times(const SpeechFiles& files, const GraphParams& params) {
  std::vector<std::string> warnings;
  audio::Audio sound = audio::read_audio(files.audio, &warnings);
  const double duration_s = sound.duration();
  audio::EnergyTrack energy = audio::energy_track(sound);
  // Before the long onset analysis: silence or a click of audio fails at once.
  if (!files.allow_silence) {
    const std::string problem = audio::speech_level_problem(duration_s, energy);
    if (!problem.empty()) throw Error(audio::speech_refusal(files.audio, problem, warnings));
  }
  std::vector<text::Word> words;
  if (!files.transcript.empty()) words = text::read_transcript(files.transcript, files.transcript_format, files.tier);
  const std::string& name = files.transcript.empty() ? files.audio : files.transcript;
  // Checked before the long onset analysis: a transcript of another recording fails at once.
  if (!files.transcript.empty()) text::check_transcript_fits(words, duration_s, name);
  audio::OnsetAnalysis onsets = audio::detect_onsets(std::move(sound), onset_params_of(params));
  if (!files.allow_silence) {
    const std::string problem =
        audio::speech_onset_problem(duration_s, onsets.onset_frames.size(), params.min_onset_strength);
    if (!problem.empty()) throw Error(audio::speech_refusal(files.audio, problem, warnings));
  }
  SpeechTimes t =
      times_of(std::move(onsets), std::move(energy), duration_s, files.transcript.empty() ? nullptr : &words, name);
  t.warnings = std::move(warnings);
  return t;
}

SpeechEvents speech_analyse(const SpeechFiles& files, double fps, int frame_count, const GraphParams& params,
                            const text::Lexicon& lexicon) {
  return speech_events_on_grid(speech_times(files, params), fps, frame_count, lexicon);
}

namespace {

// "62.0 s": durations as a user compares them.
std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}

ClipEvents read_reference(const ReferenceFiles& c, const Config& config, const text::Lexicon& lexicon,
                          std::vector<std::string>& out_warnings) {
  // The speech first: its audio (the larger of the two for long clips) is released before the
  // motion is read. A motion that cannot be opened is still reported before the long analysis.
  check_readable_file(c.motion);
  if (!c.skeleton.empty()) check_readable_file(c.skeleton);
  const SpeechTimes times = speech_times(c.speech, config.graph);
  ClipEvents in;
  in.name = c.motion;
  in.motion = motion_read(c.motion, c.skeleton);
  motion_lock_and_smooth(in.motion, config.cleanup.lock_joints, config.cleanup.smooth_window,
                         config.cleanup.smooth_order, c.motion);
  const SpeechEvents ev = speech_events_on_grid(times, in.motion.fps, in.motion.frame_count, lexicon);
  out_warnings = ev.warnings;
  const double motion_s = in.motion.frame_count / in.motion.fps;
  if (std::abs(motion_s - times.duration_s) > kMaxReferenceDurationMismatchS)
    out_warnings.push_back(c.speech.audio + ": lasts " + seconds_text(times.duration_s) + " but its motion " +
                           c.motion + " lasts " + seconds_text(motion_s) + " (" +
                           seconds_text(std::abs(motion_s - times.duration_s)) +
                           " apart): both are read from their starts, so check they are one recording");
  in.onset_frames = ev.onset_frames;
  in.keyword_frames = ev.keyword_frames;
  in.speech = ev.features.values;
  in.speech_dims = audio::SpeechFeatures::kDims;
  return in;
}

}  // namespace

MotionGraph graph_build_from_files(const std::vector<ReferenceFiles>& clips, const Config& config,
                                   const BuildProgress& progress, int jobs, std::vector<std::string>* out_warnings) {
  config_validate(config);
  const text::Lexicon lexicon = lexicon_for(config.graph);
  std::vector<ClipEvents> inputs(clips.size());
  std::vector<std::vector<std::string>> warnings(clips.size());
  std::mutex m;
  long done = 0;
  // Clips are independent: read them on several threads, each into its own slot.
  parallel_for(clips.size(), worker_count(jobs, clips.size()), [&](std::size_t i, int) {
    std::exception_ptr error;  // a clip that fails counts as read too; parallel_for reports the first
    try {
      inputs[i] = naming_memory_errors(clips[i].motion, "reading the reference clip",
                                       [&] { return read_reference(clips[i], config, lexicon, warnings[i]); });
    } catch (...) {
      error = std::current_exception();
    }
    {
      const std::lock_guard<std::mutex> lock(m);
      if (progress) progress("read", ++done, static_cast<long>(clips.size()));
    }
    if (error) std::rethrow_exception(error);
  });
  if (out_warnings)
    for (const std::vector<std::string>& w : warnings) out_warnings->insert(out_warnings->end(), w.begin(), w.end());
  const std::string what = clips.empty() ? std::string("graph") : clips.front().motion;
  return naming_memory_errors(what, "building the graph",
                              [&] { return graph_build(std::move(inputs), config.graph, progress); });
}

void check_output_size(int frames, const Skeleton& skeleton, const std::string& name) {
  const std::uint64_t bytes = static_cast<std::uint64_t>(frames) *
                              static_cast<std::uint64_t>(std::max(1, skeleton.channel_count())) *
                              limits::kBvhBytesPerValue;
  if (frames > limits::kMaxOutputFrames || bytes > limits::kMaxOutputBytes)
    throw Error(name + ": the output would have " + std::to_string(frames) + " frames of " +
                std::to_string(skeleton.channel_count()) + " channels (about " + std::to_string(bytes >> 20) +
                " MB of BVH); gmg writes at most " + std::to_string(limits::kMaxOutputFrames) + " frames and " +
                std::to_string(limits::kMaxOutputBytes >> 30) + " GB");
}

BlendParams assembly_params(const Config& config) {
  BlendParams p = config.blend;
  // The paper's planner comes with the paper's blending (SPEC: "with the cost weight at 0 and the
  // paper blending, the planner is the paper's").
  if (config.search.planner == PlannerMode::Paper) {
    p.mode = BlendMode::Crossfade;
    p.root = RootMode::Free;
  }
  return p;
}

Motion assemble_motion(const MotionGraph& g, const Plan& plan, const BlendParams& params) {
  if (params.mode == BlendMode::Inertialize) {
    std::vector<char> continues(static_cast<std::size_t>(g.frame_count()));
    for (int f = 0; f < g.frame_count(); ++f) continues[static_cast<std::size_t>(f)] = !(g.node(f).kinds & kBreakNode);
    std::vector<PathPiece> pieces;
    pieces.reserve(plan.segments.size());
    for (const PlannedSegment& s : plan.segments) pieces.push_back({s.path, s.sub.length});
    return assemble_inertialized(g.motion, continues, pieces, params);
  }
  std::vector<Motion> pieces;
  pieces.reserve(plan.segments.size());
  for (const PlannedSegment& s : plan.segments) pieces.push_back(resample_path(g.motion, s.path, s.sub.length));
  return blend_concatenate(pieces, params);
}

Reenactment reenact_events(const MotionGraph& g, const SpeechEvents& events, const Config& config) {
  config_validate(config);
  std::mt19937_64 rng(config.seed);
  const std::vector<Subsequence> subs = segment_speech(events.total_frames, events.onset_frames, events.keyword_frames);
  Reenactment r;
  r.plan = plan_reenactment(g, subs, config.search, rng, events.features.values);
  r.motion = assemble_motion(g, r.plan, assembly_params(config));

  r.report = reenactment_report(r.plan, events, config, g.motion.fps, length_unit_to_cm(g.motion.skeleton));
  r.warnings = events.warnings;
  return r;
}

std::string check_lock_joints_of_graph(const MotionGraph& g, const Config& config, const std::string& graph_name) {
  const std::vector<std::string>& joints = config.cleanup.lock_joints;
  if (joints.empty()) return "";
  std::vector<std::string> names;
  for (const Joint& j : g.motion.skeleton.joints) names.push_back(j.name);
  const auto missing = std::find_if(joints.begin(), joints.end(), [&](const std::string& j) {
    return std::find(names.begin(), names.end(), j) == names.end();
  });
  if (missing != joints.end())
    throw Error(graph_name + ": lock_joints names '" + *missing + "', which is not a joint of its skeleton" +
                did_you_mean(*missing, names));
  return graph_name + ": lock_joints has no effect on a built graph (its motion was cleaned, or not, by 'gmg build')";
}

Reenactment reenact(const MotionGraph& g, const SpeechFiles& speech, const Config& config,
                    const std::string& graph_name) {
  check_lock_joints_of_graph(g, config, graph_name);
  const text::Lexicon lexicon = lexicon_for(config.graph);
  const SpeechEvents events = speech_analyse(speech, g.motion.fps, -1, config.graph, lexicon);
  check_output_size(events.total_frames, g.motion.skeleton, speech.audio);
  Reenactment r = naming_memory_errors(speech.audio, "reenacting", [&] { return reenact_events(g, events, config); });
  nlohmann::ordered_json inputs = {
      {"graph", graph_name},
      {"audio", speech.audio},
      {"transcript",
       speech.transcript.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(speech.transcript)}};
  nlohmann::ordered_json full;
  full["tool"] = "gmg reenact";
  full["inputs"] = inputs;
  for (auto it = r.report.begin(); it != r.report.end(); ++it) full[it.key()] = it.value();
  r.report = std::move(full);
  return r;
}

}  // namespace gmg
