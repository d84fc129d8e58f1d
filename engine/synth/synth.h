// Procedural "synthetic speaker": a skeleton that gestures in time with the syllables of a
// synthetic speech signal, plus a word-timed transcript. The demo, the unit tests and the
// benchmarks use it where no real recording (BVH + WAV + transcript) can be shipped.
//
// What is generated (everything from one seeded std::mt19937_64, so the same SynthSpec gives
// byte-identical output on the same build):
// - A speech plan: a lead-in silence, then sentences of a small English grammar ("The children
//   found a huge garden.", "But her brother bought three houses.") separated by pauses of
//   0.8-1.2 s (a third of them 1.6-2.4 s); a comma inside a sentence is a pause of 0.3-0.45 s.
//   Words of 1-4 syllables at 4-5 syllables/s (faster with `style`). About one word in six is a
//   gesture keyword of assets/keywords.txt, where a speaker would say it ("this", "big",
//   "not", "never", "really", "together", ...); the others are words that lexicon lacks. Content
//   words and keywords have one stressed syllable; function words ("the", "a", "was", ...) are
//   unstressed. The transcript writes the sentences as text: a capital first letter, commas, full
//   stops.
// - Audio: each syllable is a voiced burst (fundamental 110-220 Hz with harmonics, a short
//   broadband "consonant" click at its start, attack 10 ms, exponential decay 80-150 ms);
//   stressed syllables are about twice as loud. Background noise (RMS 1e-3) everywhere. The
//   librosa-style onset detector (audio/onset.h, default parameters) finds onsets at (just
//   before) the stressed syllables.
// - Motion: a person standing and talking. The feet stay planted on the floor and the knees
//   slightly bent (5-20 degrees, solved for the hips' position every frame); every few seconds
//   the weight shifts to one leg (the hips sway over it, the other knee relaxes) or back to
//   both. Breathing, and a slow look-around of the head. While a sentence is spoken the hands
//   are up in front of the body, making a beat (a short lift, then a quick downward stroke of
//   the forearm and hand, a weaker one of the other hand) on each stressed syllable and a larger
//   emphasis gesture on each keyword, by its kind: both hands open out (size, quantity,
//   evaluation), the dominant hand points (this, here, away), both hands sweep out palms down
//   (not, never, but) or lift to the chest (very, then, always). In the pauses between sentences
//   the hands sink to rest beside the thighs. Head nods on stresses. Every curve is a sum of
//   smooth bumps (raised cosines) and low-frequency sinusoids, so the motion has no
//   frame-to-frame jumps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "audio/wav.h"
#include "engine/motion/motion.h"
#include "text/transcript.h"

namespace gmg {

struct SynthSpec {
  double duration_s = 30.0;  // > 0
  std::uint64_t seed = 1;    // same spec -> byte-identical output
  double fps = 30.0;         // > 0
  int sample_rate = 16000;   // >= 8000
  int joint_count_hint = 0;  // 0 = the default upper-body+legs skeleton (22 joints); larger
                             // values add finger chains (then face and accessory joints) until
                             // the skeleton has exactly max(22, joint_count_hint) joints
  double style = 0.0;        // 0..1: the speaker's style (gesture amplitude, tempo, voice
                             // pitch, rest pose), so two "speakers" differ
};

// The emphasis gesture a keyword carries (None for any other word).
enum class SynthGesture : std::uint8_t { None, Open, Point, Sweep, Lift };

// One syllable of the speech plan.
struct SynthSyllable {
  double time = 0;        // seconds: start of the voiced burst (its audible onset)
  bool stressed = false;  // stressed syllables are ~2x louder and carry a beat gesture
  int word = 0;           // index into SynthClip::words
};

// One phrase of the speech plan: [start, end] in seconds (first syllable start, last word end).
// A sentence is one phrase or several separated by commas.
struct SynthPhrase {
  double start = 0;
  double end = 0;
  bool ends_sentence = true;  // false: a comma, the sentence goes on after a short pause
};

struct SynthClip {
  Motion motion;                  // exactly round(duration_s * fps) frames, skeleton synth_skeleton
  audio::Audio audio;             // exactly round(duration_s * sample_rate) samples
  std::vector<text::Word> words;  // sorted, inside [0, duration]; times are whole milliseconds
  // The plan behind the data (ground truth for tests and benchmarks):
  std::vector<SynthSyllable> syllables;        // sorted by time
  std::vector<SynthPhrase> phrases;            // sorted, disjoint
  std::vector<double> keyword_times;           // start of every keyword word (seconds), sorted
  std::vector<SynthGesture> keyword_gestures;  // the gesture of each keyword (same order)
};

// Y-up, centimetres, facing +Z, T-pose at rest (identity rotations; the arms lie along +-X).
// Root "Hips" with 6 channels (Xposition Yposition Zposition Zrotation Xrotation Yrotation),
// every other joint 3 rotation channels (Zrotation Xrotation Yrotation), End Sites on leaves.
// Names follow the Mixamo/GENEA convention (Spine, Spine1, Spine2, Neck, Head, LeftShoulder,
// LeftArm, LeftForeArm, LeftHand, LeftHandIndex1, ..., LeftUpLeg, LeftLeg, LeftFoot,
// LeftToeBase, and Right*). Throws gmg::Error when joint_count_hint < 0 or > 1000.
Skeleton synth_skeleton(int joint_count_hint = 0);

// Generates a clip. Throws gmg::Error on an invalid spec (non-positive or non-finite duration
// or fps, sample_rate < 8000, style outside [0, 1], bad joint_count_hint, more than 10^8 frames
// or 10^9 samples).
SynthClip synth_speaker(const SynthSpec& spec);

// Writes dir/stem.bvh, dir/stem.wav (PCM16) and dir/stem.tsv (GENEA TSV: start<TAB>end<TAB>word,
// times with 3 decimals), each atomically. Creates dir (and its parents) when missing.
// Throws gmg::Error when something cannot be written.
void synth_write(const SynthClip& clip, const std::string& dir, const std::string& stem);

}  // namespace gmg
