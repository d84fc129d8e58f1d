// Reenacting new speech from a graph: segmentation, planning and assembly, from files, from
// speech in memory or from events already analysed, with the checks that run before any search.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "audio/wav.h"
#include "engine/config/config.h"
#include "engine/motion/motion.h"
#include "engine/pipeline/assembly.h"
#include "engine/pipeline/control.h"
#include "engine/pipeline/speech_analysis.h"
#include "graph/motion_graph.h"
#include "search/planner.h"
#include "text/transcript.h"

namespace gmg {

struct Reenactment {
  Motion motion;  // exactly events.total_frames frames, in the graph's skeleton
  // The graph's SMPL-X body (shape, gender, model) with its face: by default the face track of the
  // new speech (engine/face/face_track.h, which also drives a jaw joint of the motion); with
  // face_mode=body, or a graph without face speech, the reference face of the source time each
  // output frame plays, blended through transitions like the motion (engine/assemble/channels.h);
  // no face when the graph has none.
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
// of check_lock_joints_of_graph, which runs first. `control` (engine/pipeline/control.h): its pins
// (by word: of speech.transcript) and the earlier output it keeps, checked after the speech
// analysis and before any search, each refusal naming its file.
Reenactment reenact(const MotionGraph& g, const SpeechFiles& speech, const Config& config,
                    const std::string& graph_name, const Control& control = {});

// Same, from speech in memory (words may be null: no transcript; checked with
// check_audio_samples and check_words, and refused as a file is when it cannot be speech unless
// allow_silence). `name` labels errors and the report's audio.
Reenactment reenact_audio(const MotionGraph& g, const audio::Audio& sound, const std::vector<text::Word>* words,
                          const Config& config, const std::string& name, const std::string& graph_name,
                          bool allow_silence = false, const Control& control = {});

// Same, from events already analysed, with the control's pins and kept output already checked
// (engine/pipeline/control.h).
Reenactment reenact_events(const MotionGraph& g, const SpeechEvents& events, const Config& config,
                           const ControlFrames& control = {});

// Gives the reenactment `betas` (e.g. read_betas_file of an .npz with `betas`, or an .npy) in
// place of the graph's, and says in its report that they come from `from`.
void reenactment_use_betas(Reenactment& r, std::vector<double> betas, const std::string& from);

}  // namespace gmg
