// A motion graph built from reference clips: files read and analysed in parallel waves, or clips
// already in memory (the Python module's arrays), analysed alike.
#pragma once

#include <string>
#include <vector>

#include "audio/wav.h"
#include "engine/config/config.h"
#include "engine/motion/motion.h"
#include "engine/pipeline/speech_analysis.h"
#include "graph/build.h"
#include "text/transcript.h"

namespace gmg {

// A reference whose audio and motion durations differ by more than this many seconds gets a
// warning naming both files: they are put on one clock from their starts, so a large difference
// means a cut recording or files of two recordings.
inline constexpr double kMaxReferenceDurationMismatchS = 1.0;

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
  bool has_words = false;      // false: no transcript
  bool allow_silence = false;  // as SpeechFiles::allow_silence: audio that cannot be speech is refused
};

// graph_build_from_files for clips in memory (checked with check_audio_samples, check_words,
// motion_check_finite), in the order given.
MotionGraph graph_build_from_clips(std::vector<ReferenceClip> clips, const Config& config);

}  // namespace gmg
