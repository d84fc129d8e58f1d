// The synthetic speaker's steps in order (speech plan, motion, audio) and the writing of a clip.
// The steps live in the other synth_*.cpp files (see synth_internal.h).
#include "engine/synth/synth.h"

#include <filesystem>
#include <locale>
#include <ostream>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"
#include "engine/motion/bvh.h"
#include "engine/synth/synth_internal.h"

namespace gmg {
namespace {

void check_spec(const SynthSpec& spec) {
  auto bad = [](const std::string& what) { throw Error("synth_speaker: " + what); };
  if (!std::isfinite(spec.duration_s) || spec.duration_s <= 0) bad("duration_s must be a positive number");
  if (!std::isfinite(spec.fps) || spec.fps <= 0) bad("fps must be a positive number");
  if (spec.sample_rate < 8000) bad("sample_rate must be at least 8000");
  if (!(spec.style >= 0.0 && spec.style <= 1.0)) bad("style must lie in [0, 1]");
  if (spec.sample_rate > limits::kMaxSampleRate)
    bad("sample_rate must be at most " + std::to_string(limits::kMaxSampleRate));
  // The output limits of every generated clip (engine/core/limits.h), checked before any work.
  if (spec.duration_s > limits::kMaxAudioSeconds)
    bad("duration_s must be at most " + format_number(limits::kMaxAudioSeconds) + " (a day)");
  if (spec.duration_s * spec.fps > limits::kMaxOutputFrames)
    bad("clip too long (more than " + std::to_string(limits::kMaxOutputFrames) + " frames)");
}

}  // namespace

SynthClip synth_speaker(const SynthSpec& spec) {
  using namespace synth_internal;
  check_spec(spec);
  (void)synth_skeleton(spec.joint_count_hint);  // validates the hint before any work
  const int frame_count = static_cast<int>(std::llround(spec.duration_s * spec.fps));
  const auto sample_count = static_cast<std::size_t>(std::llround(spec.duration_s * spec.sample_rate));

  Rng plan_rng(spec.seed, 1), audio_rng(spec.seed, 2), motion_rng(spec.seed, 3);
  SpeechPlan plan = plan_speech(spec.duration_s, spec.style, plan_rng);

  SynthClip clip;
  clip.motion = synth_motion(plan, spec, frame_count, motion_rng);
  clip.audio = synth_audio(plan, spec, sample_count, audio_rng);
  clip.words = std::move(plan.words);
  clip.syllables = std::move(plan.syllables);
  clip.phrases = std::move(plan.phrases);
  clip.keyword_times = std::move(plan.keyword_times);
  clip.keyword_gestures = std::move(plan.keyword_gestures);
  return clip;
}

void synth_write(const SynthClip& clip, const std::string& dir, const std::string& stem) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create folder (" + ec.message() + ")");
  const std::filesystem::path base = std::filesystem::path(dir) / stem;
  bvh_write(base.string() + ".bvh", clip.motion);
  audio::write_wav_pcm16(base.string() + ".wav", clip.audio);
  write_file_atomically(base.string() + ".tsv", [&clip](std::ostream& out) {
    std::ostringstream os;
    os.imbue(std::locale::classic());
    os.setf(std::ios::fixed);
    os.precision(3);
    for (const text::Word& w : clip.words) os << w.start << '\t' << w.end << '\t' << w.text << '\n';
    out << os.str();
  });
}

}  // namespace gmg
