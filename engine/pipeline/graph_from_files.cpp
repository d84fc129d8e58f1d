#include "engine/pipeline/graph_from_files.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <thread>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/parallel.h"
#include "engine/face/reference_speech.h"
#include "engine/motion/cleanup.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/up_axis.h"

namespace gmg {

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
// kMaxReferenceDurationMismatchS apart; out_face what the face track keeps of the speech.
ClipEvents clip_events(Motion motion, const SpeechTimes& times, const Config& config, const text::Lexicon& lexicon,
                       const std::string& name, const std::string& speech_name, std::vector<std::string>& out_warnings,
                       ClipFaceSpeech& out_face) {
  ClipEvents in;
  in.name = name;
  in.motion = std::move(motion);
  in.up = resolve_up_axis(in.motion, config.graph.up);
  motion_to_y_up(in.motion, in.up);
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
  out_face.features = ev.face_features.values;
  out_face.phones = ev.phones;
  return in;
}

// Files up to this size are read side by side when a core is free: the motion's reading then
// overlaps the speech's analysis, and the peak grows by the smaller of the two in memory. The
// limit is on both files, since a file's size says little about its decoded size (a compressed
// audio file decodes to many times its size): 32 MiB is about 17 minutes of 16 kHz 16-bit WAV, 24
// of 25-joint BVH (what an hour's clip read side by side costs: docs/performance.md).
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
                          SmplxBody& out_body, std::vector<std::string>& out_warnings, ClipFaceSpeech& out_face) {
  check_readable_file(c.motion);
  if (!c.skeleton.empty()) check_readable_file(c.skeleton);
  if (!alongside || !small_enough_alongside(c.speech.audio, c.motion)) {
    const SpeechTimes times = speech_times(c.speech, config.graph);
    return clip_events(motion_read(c.motion, c.skeleton, &out_body), times, config, lexicon, c.motion, c.speech.audio,
                       out_warnings, out_face);
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
  return clip_events(std::move(motion), times, config, lexicon, c.motion, c.speech.audio, out_warnings, out_face);
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
  std::vector<ClipFaceSpeech> faces(clips.size());
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
          return read_reference(clip, config, lexicon, alongside, bodies[first + i], warnings[i], faces[first + i]);
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
  g.face_speech = face_speech_of(g, faces);
  return g;
}

MotionGraph graph_build_from_clips(std::vector<ReferenceClip> clips, const Config& config) {
  config_validate(config);
  const text::Lexicon lexicon = lexicon_for(config.graph);
  std::vector<ClipEvents> inputs;
  std::vector<SmplxBody> bodies;
  std::vector<ClipFaceSpeech> faces(clips.size());
  inputs.reserve(clips.size());
  std::size_t index = 0;
  for (ReferenceClip& c : clips) {
    check_audio_samples(c.sound, c.name);
    if (c.has_words) check_words(c.words, c.name);
    motion_check_finite(c.motion, c.name);
    if (c.body.has_face() && c.body.expressions.size() != static_cast<std::size_t>(c.motion.frame_count) *
                                                              static_cast<std::size_t>(c.body.expression_dims))
      throw Error(c.name + ": the face does not have the motion's " + std::to_string(c.motion.frame_count) + " frames");
    inputs.push_back(naming_memory_errors(c.name, "reading the reference clip", [&] {
      const SpeechTimes times =
          speech_times_of(c.sound, c.has_words ? &c.words : nullptr, c.name, config.graph, c.allow_silence);
      std::vector<std::string> warnings;  // the arrays' caller has them in hand: none is news
      return clip_events(std::move(c.motion), times, config, lexicon, c.name, c.name, warnings, faces[index]);
    }));
    ++index;
    bodies.push_back(std::move(c.body));
  }
  const std::string what = clips.empty() ? std::string("graph") : clips.front().name;
  MotionGraph g =
      naming_memory_errors(what, "building the graph", [&] { return graph_build(std::move(inputs), config.graph); });
  g.body = join_bodies(bodies);
  g.face_speech = face_speech_of(g, faces);
  return g;
}

}  // namespace gmg
