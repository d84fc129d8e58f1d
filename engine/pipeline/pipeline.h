// The engine's jobs: analyse speech into timed events, build a graph from reference files,
// reenact new speech from a graph. The command-line tool and batch runs call these.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "audio/onset.h"
#include "audio/speech_features.h"
#include "audio/wav.h"
#include "engine/config/config.h"
#include "engine/motion/motion.h"
#include "graph/build.h"
#include "search/planner.h"
#include "text/keywords.h"
#include "text/transcript.h"

namespace gmg {

// One speech: an audio file and, optionally, a word-timed transcript.
struct SpeechFiles {
  std::string audio;       // audio path (required): WAV, or any format audio/audio_file.h reads
  std::string transcript;  // "" = none
  text::TranscriptFormat transcript_format = text::TranscriptFormat::Auto;
  std::string tier{};  // the TextGrid tier to read; "" = the default (text/transcript.h read_textgrid)
  // Take audio that cannot be speech as it is: shorter than 0.5 s, silent, or without any onset
  // in more than 10 s (audio/speech_check.h). false: such audio is an error naming the file.
  bool allow_silence = false;
};

// A reference whose audio and motion durations differ by more than this many seconds gets a
// warning naming both files: they are put on one clock from their starts, so a large difference
// means a cut recording or files of two recordings.
inline constexpr double kMaxReferenceDurationMismatchS = 1.0;

// Speech as frames on a motion grid.
struct SpeechEvents {
  double duration_s = 0.0;        // audio duration
  int total_frames = 0;           // round(duration_s * fps) for test speech; the motion length for a reference
  std::vector<int> onset_frames;  // ascending, unique, in [0, total_frames)
  std::vector<std::pair<int, std::string>> keyword_frames;  // ascending, in [0, total_frames)
  int words = 0;                                            // transcript words read
  audio::SpeechFeatures features;                           // total_frames frames
  std::vector<std::string> warnings;  // what did not stop the analysis (decoder damage), naming the file
};

// Detects onsets (SPEC "Onset nodes") and keywords in a speech. frame_count < 0 means a test
// speech (T = round(duration * fps)); otherwise events at or after frame_count are dropped (a
// reference whose audio outlasts its motion). A transcript that runs past the audio's end is an
// error naming the transcript; audio that cannot be speech (audio/speech_check.h) is an error
// naming the audio unless files.allow_silence.
SpeechEvents speech_analyse(const SpeechFiles& files, double fps, int frame_count, const GraphParams& params,
                            const text::Lexicon& lexicon);

// Speech analysed in seconds, before it is put on a motion's frame grid. A reference's audio is
// analysed (and released) before its motion is read, so the two are never in memory together.
struct SpeechTimes {
  double duration_s = 0.0;
  audio::OnsetAnalysis onsets;
  audio::EnergyTrack energy;
  std::vector<text::Word> words;
  bool has_words = false;
  std::string name;                   // labels errors: the transcript's file name, else the audio's
  std::vector<std::string> warnings;  // what did not stop the reading (decoder damage), naming the file
};

// Reads and analyses a speech (the transcript past the audio's end and audio that cannot be
// speech are errors here already).
SpeechTimes speech_times(const SpeechFiles& files, const GraphParams& params);

// The events of analysed speech on a grid of `fps` (frame_count as for speech_analyse).
SpeechEvents speech_events_on_grid(const SpeechTimes& times, double fps, int frame_count, const text::Lexicon& lexicon);

// Analyses speech in memory (words may be null: no transcript); `name` labels errors.
SpeechTimes speech_times_of(const audio::Audio& sound, const std::vector<text::Word>* words, const std::string& name,
                            const GraphParams& params);

// Audio given in memory, checked as the readers check a file's: gmg::Error "name: ..." for a
// sample rate outside engine/core/limits.h, no samples, more than a day, or a value that is not
// finite.
void check_audio_samples(const audio::Audio& sound, const std::string& name);

// Words given in memory, checked as the transcript readers check a file's (finite times, 0 <=
// start <= end, non-empty text) and sorted by start time as they sort them.
void check_words(std::vector<text::Word>& words, const std::string& name);

// Same as speech_analyse, from audio and words already in memory (words may be null: no
// transcript). `name` labels errors (the transcript's file name).
SpeechEvents speech_events(const audio::Audio& sound, const std::vector<text::Word>* words, const std::string& name,
                           double fps, int frame_count, const GraphParams& params, const text::Lexicon& lexicon);

// The lexicon named by params.keywords, or assets/keywords.txt.
text::Lexicon lexicon_for(const GraphParams& params);

struct ReferenceFiles {
  std::string motion;  // BVH or SMPL-X .npz path
  SpeechFiles speech;
  std::string skeleton{};  // BVH skeleton template of an .npz motion (engine/motion/npz.h); "" = none
};

// Reads, analyses and joins the clips into one graph, in the order given. Clips are read by up
// to `jobs` threads (0: every core), that many at a time, and each joins the graph as soon as it
// and the ones before it are read (graph/build.h GraphBuild), so memory holds a few clips, not
// all; past a limit their motion and features go to temporary files in `spill_folder` ("" keeps
// them in memory). A problem names the first clip (in order) that has one. Warnings (each naming
// its files: decoder damage, a clip whose audio and motion durations differ by more than
// kMaxReferenceDurationMismatchS) are added to *out_warnings in clip order, when it is given.
MotionGraph graph_build_from_files(const std::vector<ReferenceFiles>& clips, const Config& config,
                                   const BuildProgress& progress = {}, int jobs = 1,
                                   std::vector<std::string>* out_warnings = nullptr,
                                   const std::string& spill_folder = "");

// A reference clip in memory (the Python module's arrays): analysed exactly as a clip of files.
struct ReferenceClip {
  std::string name;  // labels errors and the graph's clip table
  Motion motion;
  SmplxBody body{};  // the face must have the motion's frame count
  audio::Audio sound;
  std::vector<text::Word> words{};
  bool has_words = false;  // false: no transcript
};

// graph_build_from_files for clips in memory (checked with check_audio_samples, check_words,
// motion_check_finite), in the order given.
MotionGraph graph_build_from_clips(std::vector<ReferenceClip> clips, const Config& config);

struct Reenactment {
  Motion motion;  // exactly events.total_frames frames, in the graph's skeleton
  // The graph's SMPL-X body (shape, gender, model) with the face played along the motion: each
  // output frame has the reference face of the source time it plays, blended through
  // transitions like the motion (engine/assemble/channels.h); no face when the graph has none.
  SmplxBody body;
  Plan plan;
  nlohmann::ordered_json report;
  std::vector<std::string> warnings;  // what did not stop it, each naming its file (for standard error)
};

// Throws gmg::Error naming `graph_name` when config.cleanup.lock_joints names a joint g's
// skeleton lacks (with the nearest joint name). A built graph's motion was cleaned when it was
// built, so for joints it has, the warning returned says the key has no effect here; "" when
// lock_joints is empty.
std::string check_lock_joints_of_graph(const MotionGraph& g, const Config& config, const std::string& graph_name);

// Throws gmg::Error naming `name` (the speech) when a motion of `frames` frames in `skeleton`
// would exceed what gmg writes (engine/core/limits.h: kMaxOutputFrames frames, kMaxOutputBytes
// of BVH text). reenact checks it before any search.
void check_output_size(int frames, const Skeleton& skeleton, const std::string& name);

// Reenacts the speech: segmentation, planning, resampling, blending. Deterministic for a given
// graph, speech, config (including config.seed). `graph_name` labels the report and the errors
// of check_lock_joints_of_graph, which runs first.
Reenactment reenact(const MotionGraph& g, const SpeechFiles& speech, const Config& config,
                    const std::string& graph_name);

// Same, from speech in memory (words may be null: no transcript; checked with
// check_audio_samples and check_words). `name` labels errors and the report's audio.
Reenactment reenact_audio(const MotionGraph& g, const audio::Audio& sound, const std::vector<text::Word>* words,
                          const Config& config, const std::string& name, const std::string& graph_name);

// Same, from events already analysed.
Reenactment reenact_events(const MotionGraph& g, const SpeechEvents& events, const Config& config);

// The assembly parameters a configuration implies: config.blend, except that the paper's planner
// joins pieces with the paper's cross-fade and a free root.
BlendParams assembly_params(const Config& config);

// Paths of a plan joined into one motion: by source time with inertialized transitions
// (BlendMode::Inertialize), or resampled to their target lengths and blended (Offset, Crossfade).
Motion assemble_motion(const MotionGraph& g, const Plan& plan, const BlendParams& params);

// The graph's body along a plan: its shape and labels, and its face assembled as assemble_motion
// assembles the motion (the same clock and transitions); no face when the graph has none.
SmplxBody assemble_body(const MotionGraph& g, const Plan& plan, const BlendParams& params);

// What a report says of an output's body, for an SMPL-X skeleton or a body (else null): {"face":
// "reference" | "none", "betas": betas_from (when the body has betas) | "none", "note": what an
// .npz output holds in place of what is missing}.
nlohmann::ordered_json body_report(const Skeleton& skeleton, const SmplxBody& body,
                                   const std::string& betas_from = "reference");

// Gives the reenactment `betas` (e.g. read_betas_file of an .npz with `betas`, or an .npy) in
// place of the graph's, and says in its report that they come from `from`.
void reenactment_use_betas(Reenactment& r, std::vector<double> betas, const std::string& from);

}  // namespace gmg
