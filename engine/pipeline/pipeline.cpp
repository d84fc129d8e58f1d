#include "engine/pipeline/pipeline.h"
#include "engine/pipeline/lower_body.h"

#include "engine/pipeline/report.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <random>
#include <thread>

#include "audio/audio_file.h"
#include "audio/onset.h"
#include "audio/speech_check.h"
#include "engine/assemble/blend.h"
#include "engine/assemble/channels.h"
#include "engine/assemble/resample.h"
#include "engine/assemble/transitions.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/limits.h"
#include "engine/core/parallel.h"
#include "engine/core/strings.h"
#include "engine/metrics/evaluate.h"
#include "engine/motion/capture_facts.h"
#include "engine/motion/cleanup.h"
#include "engine/motion/motion_file.h"
#include "graph/graph_io.h"
#include "graph/reference_facts.h"
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

SpeechTimes speech_times_of(const audio::Audio& sound, const std::vector<text::Word>* words, const std::string& name,
                            const GraphParams& params) {
  return times_of(audio::detect_onsets(sound, onset_params_of(params)), audio::energy_track(sound), sound.duration(),
                  words, name);
}

SpeechEvents speech_events(const audio::Audio& sound, const std::vector<text::Word>* words, const std::string& name,
                           double fps, int frame_count, const GraphParams& params, const text::Lexicon& lexicon) {
  return speech_events_on_grid(speech_times_of(sound, words, name, params), fps, frame_count, lexicon);
}

void check_audio_samples(const audio::Audio& sound, const std::string& name) {
  if (sound.sample_rate < limits::kMinSampleRate || sound.sample_rate > limits::kMaxSampleRate)
    throw Error(name + ": sample rate " + std::to_string(sound.sample_rate) + " Hz is outside the " +
                std::to_string(limits::kMinSampleRate) + " to " + std::to_string(limits::kMaxSampleRate) +
                " Hz gmg reads");
  if (sound.samples.empty()) throw Error(name + ": the audio has no samples");
  if (sound.duration() > limits::kMaxAudioSeconds)
    throw Error(name + ": " + format_number(sound.duration()) + " s of audio is more than the " +
                format_number(limits::kMaxAudioSeconds) + " s gmg reads");
  for (std::size_t i = 0; i < sound.samples.size(); ++i)
    if (!std::isfinite(sound.samples[i]))
      throw Error(name + ": sample " + std::to_string(i) + " is not a finite number");
}

void check_words(std::vector<text::Word>& words, const std::string& name) {
  for (std::size_t i = 0; i < words.size(); ++i) {
    const text::Word& w = words[i];
    if (!std::isfinite(w.start) || !std::isfinite(w.end) || w.start < 0 || w.end < w.start)
      throw Error(name + ": word " + std::to_string(i + 1) + " ('" + w.text + "') has times " + format_number(w.start) +
                  " to " + format_number(w.end) + " s; a word needs 0 <= start <= end, finite");
    if (w.text.empty()) throw Error(name + ": word " + std::to_string(i + 1) + " is empty");
  }
  // The readers' order (text/transcript.h): by start time, ties in the given order.
  std::stable_sort(words.begin(), words.end(),
                   [](const text::Word& a, const text::Word& b) { return a.start < b.start; });
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

// A reference clip's motion and analysed speech as the graph takes them: the motion cleaned up
// (config.cleanup), the events on its frame grid; out_warnings gets the speech's warnings and one
// when the speech (`speech_name`) and the motion (`name`) last more than
// kMaxReferenceDurationMismatchS apart.
ClipEvents clip_events(Motion motion, const SpeechTimes& times, const Config& config, const text::Lexicon& lexicon,
                       const std::string& name, const std::string& speech_name,
                       std::vector<std::string>& out_warnings) {
  ClipEvents in;
  in.name = name;
  in.motion = std::move(motion);
  motion_lock_and_smooth(in.motion, config.cleanup.lock_joints, config.cleanup.smooth_window,
                         config.cleanup.smooth_order, name);
  const SpeechEvents ev = speech_events_on_grid(times, in.motion.fps, in.motion.frame_count, lexicon);
  out_warnings = ev.warnings;
  const double motion_s = in.motion.frame_count / in.motion.fps;
  if (std::abs(motion_s - times.duration_s) > kMaxReferenceDurationMismatchS)
    out_warnings.push_back(speech_name + ": lasts " + seconds_text(times.duration_s) + " but its motion " + name +
                           " lasts " + seconds_text(motion_s) + " (" +
                           seconds_text(std::abs(motion_s - times.duration_s)) +
                           " apart): both are read from their starts, so check they are one recording");
  in.onset_frames = ev.onset_frames;
  in.keyword_frames = ev.keyword_frames;
  in.speech = ev.features.values;
  in.speech_dims = audio::SpeechFeatures::kDims;
  return in;
}

// Files up to this size are read side by side when a core is free: the motion's reading then
// overlaps the speech's analysis, and the peak grows by the smaller of the two in memory. The
// limit is on both files, since a file's size says little about its decoded size (a compressed
// audio file decodes to many times its size): 32 MiB is about 17 minutes of 16 kHz 16-bit WAV, 24
// of 25-joint BVH. (A one-hour clip, 115 MB of audio and 79 MB of BVH, peaked 116 MiB
// higher read side by side.)
constexpr std::uintmax_t kAlongsideFileBytes = std::uintmax_t{32} << 20;

// Whether both files exist and are at most kAlongsideFileBytes.
bool small_enough_alongside(const std::string& a, const std::string& b) {
  std::error_code error_a, error_b;
  const std::uintmax_t size_a = std::filesystem::file_size(a, error_a), size_b = std::filesystem::file_size(b, error_b);
  return !error_a && !error_b && size_a <= kAlongsideFileBytes && size_b <= kAlongsideFileBytes;
}

// With `alongside` and both files up to kAlongsideFileBytes, the motion is read on this thread
// while the speech is analysed on a second (a core would otherwise wait: a build of one clip);
// else the speech first, so that its audio (the larger of the two for long clips) is released
// before the motion is read. Either way a motion that cannot be opened is reported before the long
// analysis, and a speech error before a motion error.
ClipEvents read_reference(const ReferenceFiles& c, const Config& config, const text::Lexicon& lexicon, bool alongside,
                          SmplxBody& out_body, std::vector<std::string>& out_warnings) {
  check_readable_file(c.motion);
  if (!c.skeleton.empty()) check_readable_file(c.skeleton);
  if (!alongside || !small_enough_alongside(c.speech.audio, c.motion)) {
    const SpeechTimes times = speech_times(c.speech, config.graph);
    return clip_events(motion_read(c.motion, c.skeleton, &out_body), times, config, lexicon, c.motion, c.speech.audio,
                       out_warnings);
  }
  // The speech on a second thread, the motion on this one: the motion's many small allocations stay
  // in this thread's heap (a second thread's would start a heap of its own and fault its pages in),
  // the audio's few large arrays are mapped wherever they are made.
  SpeechTimes times;
  std::exception_ptr speech_error, motion_error;
  std::thread speech([&] {
    try {
      times = speech_times(c.speech, config.graph);
    } catch (...) {
      speech_error = std::current_exception();
    }
  });
  Motion motion;
  try {
    motion = motion_read(c.motion, c.skeleton, &out_body);
  } catch (...) {
    motion_error = std::current_exception();
  }
  speech.join();
  if (speech_error) std::rethrow_exception(speech_error);
  if (motion_error) std::rethrow_exception(motion_error);
  return clip_events(std::move(motion), times, config, lexicon, c.motion, c.speech.audio, out_warnings);
}

// The graph's body from its clips': the face when every clip has one of the same size (a face
// for only some clips would leave the others' frames without one), the shape and labels of the
// first clip that has them.
SmplxBody join_bodies(std::vector<SmplxBody>& bodies) {
  SmplxBody out;
  if (bodies.empty()) return out;
  const int dims = bodies.front().expression_dims;
  bool faces = dims > 0;
  for (const SmplxBody& b : bodies) faces = faces && b.expression_dims == dims;
  if (faces) {
    out.expression_dims = dims;
    if (bodies.size() == 1) {
      out.expressions = std::move(bodies.front().expressions);
    } else {
      for (const SmplxBody& b : bodies)
        out.expressions.insert(out.expressions.end(), b.expressions.begin(), b.expressions.end());
    }
  }
  for (const SmplxBody& b : bodies) {
    if (out.betas.empty()) out.betas = b.betas;
    if (out.gender.empty()) out.gender = b.gender;
    if (out.model.empty()) out.model = b.model;
  }
  return out;
}

}  // namespace

MotionGraph graph_build_from_files(const std::vector<ReferenceFiles>& clips, const Config& config,
                                   const BuildProgress& progress, int jobs, std::vector<std::string>* out_warnings,
                                   const std::string& spill_folder) {
  config_validate(config);
  const text::Lexicon lexicon = lexicon_for(config.graph);
  const std::string what = clips.empty() ? std::string("graph") : clips.front().motion;
  GraphBuild build(config.graph, spill_folder);
  std::vector<SmplxBody> bodies(clips.size());
  const int workers = worker_count(jobs, clips.size());
  // Cores left over by a wave of clips (one clip on two cores): each clip reads its motion alongside
  // its speech.
  const bool alongside = worker_count(jobs) >= 2 * workers && clips.size() <= static_cast<std::size_t>(workers);
  long done = 0;
  // A wave of `workers` clips is read on as many threads, each into its own slot; then they join
  // the graph in order and the next wave is read.
  for (std::size_t first = 0; first < clips.size(); first += static_cast<std::size_t>(workers)) {
    const std::size_t count = std::min(clips.size() - first, static_cast<std::size_t>(workers));
    std::vector<ClipEvents> inputs(count);
    std::vector<std::vector<std::string>> warnings(count);
    std::mutex m;
    parallel_for(count, workers, [&](std::size_t i, int) {
      const ReferenceFiles& clip = clips[first + i];
      std::exception_ptr error;  // a clip that fails counts as read too; parallel_for reports the first
      try {
        inputs[i] = naming_memory_errors(clip.motion, "reading the reference clip", [&] {
          return read_reference(clip, config, lexicon, alongside, bodies[first + i], warnings[i]);
        });
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
    for (ClipEvents& c : inputs) {
      naming_memory_errors(what, "building the graph", [&] {
        build.add(std::move(c));
        return 0;
      });
      c = ClipEvents();  // release the clip's copy early
    }
  }
  MotionGraph g = naming_memory_errors(what, "building the graph", [&] { return build.finish(progress); });
  g.body = join_bodies(bodies);
  return g;
}

MotionGraph graph_build_from_clips(std::vector<ReferenceClip> clips, const Config& config) {
  config_validate(config);
  const text::Lexicon lexicon = lexicon_for(config.graph);
  std::vector<ClipEvents> inputs;
  std::vector<SmplxBody> bodies;
  inputs.reserve(clips.size());
  for (ReferenceClip& c : clips) {
    check_audio_samples(c.sound, c.name);
    if (c.has_words) check_words(c.words, c.name);
    motion_check_finite(c.motion, c.name);
    if (c.body.has_face() && c.body.expressions.size() != static_cast<std::size_t>(c.motion.frame_count) *
                                                              static_cast<std::size_t>(c.body.expression_dims))
      throw Error(c.name + ": the face does not have the motion's " + std::to_string(c.motion.frame_count) + " frames");
    inputs.push_back(naming_memory_errors(c.name, "reading the reference clip", [&] {
      const SpeechTimes times = speech_times_of(c.sound, c.has_words ? &c.words : nullptr, c.name, config.graph);
      std::vector<std::string> warnings;  // the arrays' caller has them in hand: none is news
      return clip_events(std::move(c.motion), times, config, lexicon, c.name, c.name, warnings);
    }));
    bodies.push_back(std::move(c.body));
  }
  const std::string what = clips.empty() ? std::string("graph") : clips.front().name;
  MotionGraph g =
      naming_memory_errors(what, "building the graph", [&] { return graph_build(std::move(inputs), config.graph); });
  g.body = join_bodies(bodies);
  return g;
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

namespace {

std::vector<PathPiece> plan_pieces(const Plan& plan) {
  std::vector<PathPiece> pieces;
  pieces.reserve(plan.segments.size());
  for (const PlannedSegment& s : plan.segments) pieces.push_back({s.path, s.sub.length});
  return pieces;
}

// Checks the frames the assembly reads, for a graph whose motion is checked when used
// (graph/graph_io.h graph_check_frames; nothing for others): each stretch of consecutive frames
// of each piece, and kMargin frames either side of it (the assembly samples between a frame and
// its successor, and a transition continues the old source a step at its warp rate past its last
// frame). Blocks of 64 frames make the margin cost little.
void check_played_frames(const MotionGraph& g, const Plan& plan) {
  constexpr int kMargin = 8;
  for (const PlannedSegment& s : plan.segments) {
    const std::vector<int>& p = s.path;
    for (std::size_t i = 0; i < p.size();) {
      std::size_t j = i + 1;
      while (j < p.size() && p[j] == p[j - 1] + 1) ++j;
      graph_check_frames(g, p[i] - kMargin, p[j - 1] + kMargin);
      i = j;
    }
  }
}

}  // namespace

Motion assemble_motion(const MotionGraph& g, const Plan& plan, const BlendParams& params) {
  check_played_frames(g, plan);
  if (params.mode == BlendMode::Inertialize) {
    // The graph's capture facts, so that only the frames played are read; a graph made without
    // them (by hand) has them computed from every frame.
    const CaptureRuns runs = graph_runs(g);
    return assemble_inertialized(g.motion, runs, g.capture.known ? g.capture : capture_facts(g.motion, runs),
                                 plan_pieces(plan), params);
  }
  std::vector<Motion> pieces;
  pieces.reserve(plan.segments.size());
  for (const PlannedSegment& s : plan.segments) {
    pieces.push_back(resample_path(g.motion, s.path, s.sub.length));
    motion_release_pages(g.motion);  // each piece reads another stretch of a graph served from its file
  }
  return blend_concatenate(pieces, params);
}

SmplxBody assemble_body(const MotionGraph& g, const Plan& plan, const BlendParams& params) {
  SmplxBody out;
  out.betas = g.body.betas;
  out.gender = g.body.gender;
  out.model = g.body.model;
  if (!g.body.has_face()) return out;
  out.expression_dims = g.body.expression_dims;
  out.expressions =
      params.mode == BlendMode::Inertialize
          ? assemble_channels_inertialized(g.body.expressions, g.body.expression_dims, graph_runs(g), plan_pieces(plan),
                                           params.halflife_s * g.motion.fps)
          : assemble_channels_blended(g.body.expressions, g.body.expression_dims, plan_pieces(plan), params);
  return out;
}

nlohmann::ordered_json body_report(const Skeleton& skeleton, const SmplxBody& body, const std::string& betas_from) {
  const bool face = body.has_face(), betas = !body.betas.empty();
  if (!face && !betas && !has_smplx_names(skeleton)) return nullptr;
  nlohmann::ordered_json j;
  j["face"] = face ? "reference" : "none";
  j["betas"] = betas ? betas_from : "none";
  std::string note;
  if (!face)
    note = "the reference has no face (no SMPL-X .npz with expressions): an .npz output's expressions are zeros";
  if (!betas)
    note += std::string(note.empty() ? "" : "; ") +
            "the reference has no body shape: an .npz output's betas are zeros (--betas FILE gives them)";
  if (!note.empty()) j["note"] = note;
  return j;
}

void reenactment_use_betas(Reenactment& r, std::vector<double> betas, const std::string& from) {
  r.body.betas = std::move(betas);
  r.report["body"] = body_report(r.motion.skeleton, r.body, from);
}

Reenactment reenact_events(const MotionGraph& g, const SpeechEvents& events, const Config& config) {
  config_validate(config);
  std::mt19937_64 rng(config.seed);
  const std::vector<Subsequence> subs = segment_speech(events.total_frames, events.onset_frames, events.keyword_frames);
  Reenactment r;
  r.plan = plan_reenactment(g, subs, config.search, rng, events.features.values);
  const LowerBody lower =
      plan_lower_body(g, pause_track(events.features.values, events.total_frames), events.total_frames, config, rng);
  r.motion = lower.layers.layered() ? assemble_layered(g, r.plan, lower, assembly_params(config))
                                    : assemble_motion(g, r.plan, assembly_params(config));
  r.body = assemble_body(g, r.plan, assembly_params(config));
  g.check_unchanged();  // a graph file cut short or rewritten meanwhile gave zeros or other values

  r.report =
      reenactment_report(r.plan, events, config, g.motion.fps, length_unit_to_cm(g.motion.skeleton), g.has_speech());
  if (nlohmann::ordered_json body = body_report(g.motion.skeleton, r.body); !body.is_null())
    r.report["body"] = std::move(body);
  if (nlohmann::ordered_json legs = lower_body_report(g.motion.skeleton, lower); !legs.is_null())
    r.report["lower_body"] = std::move(legs);
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

namespace {

// The report of a whole reenactment: the tool and its inputs first, then reenact_events' report.
void prepend_inputs(Reenactment& r, nlohmann::ordered_json inputs) {
  nlohmann::ordered_json full;
  full["tool"] = "gmg reenact";
  full["inputs"] = std::move(inputs);
  for (auto it = r.report.begin(); it != r.report.end(); ++it) full[it.key()] = it.value();
  r.report = std::move(full);
}

}  // namespace

Reenactment reenact(const MotionGraph& g, const SpeechFiles& speech, const Config& config,
                    const std::string& graph_name) {
  check_lock_joints_of_graph(g, config, graph_name);
  const text::Lexicon lexicon = lexicon_for(config.graph);
  const SpeechEvents events = speech_analyse(speech, g.motion.fps, -1, config.graph, lexicon);
  check_output_size(events.total_frames, g.motion.skeleton, speech.audio);
  Reenactment r = naming_memory_errors(speech.audio, "reenacting", [&] { return reenact_events(g, events, config); });
  prepend_inputs(r, {{"graph", graph_name},
                     {"audio", speech.audio},
                     {"transcript", speech.transcript.empty() ? nlohmann::ordered_json(nullptr)
                                                              : nlohmann::ordered_json(speech.transcript)}});
  return r;
}

Reenactment reenact_audio(const MotionGraph& g, const audio::Audio& sound, const std::vector<text::Word>* words,
                          const Config& config, const std::string& name, const std::string& graph_name) {
  check_lock_joints_of_graph(g, config, graph_name);
  check_audio_samples(sound, name);
  std::vector<text::Word> sorted;
  if (words) {
    sorted = *words;
    check_words(sorted, name);
  }
  const text::Lexicon lexicon = lexicon_for(config.graph);
  const SpeechEvents events =
      speech_events(sound, words ? &sorted : nullptr, name, g.motion.fps, -1, config.graph, lexicon);
  check_output_size(events.total_frames, g.motion.skeleton, name);
  Reenactment r = naming_memory_errors(name, "reenacting", [&] { return reenact_events(g, events, config); });
  prepend_inputs(r, {{"graph", graph_name}, {"audio", name}, {"transcript", nullptr}});
  return r;
}

}  // namespace gmg
