// Internals of the synthetic speaker shared by its steps; the interface is synth.h.
//
//   synth_skeleton.cpp  the skeleton (synth_skeleton)
//   synth_speech.cpp    the speech plan: phrases, words, syllables
//   synth_audio.cpp     the speech audio of a plan
//   synth_motion.cpp    the gestures of a plan
//   synth.cpp           synth_speaker (the steps in order) and synth_write
//
// Determinism: every random number comes from std::mt19937_64 through the helpers of class Rng
// (never std::uniform_*_distribution, whose output is implementation-defined). The speech plan,
// the audio noise and the motion each have their own generator, seeded from the spec's seed, so
// e.g. a change in how the audio is drawn never changes the motion. Within a step, the order of
// the draws is part of the output: reordering them changes every file.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "engine/core/math.h"
#include "engine/synth/synth.h"

namespace gmg::synth_internal {

inline constexpr int kMaxJoints = 1000;

// Finger names in chain order (the thumb last), as in "LeftHandIndex1".
inline const char* const kFingers[5] = {"Index", "Middle", "Ring", "Pinky", "Thumb"};

// ---- Randomness ------------------------------------------------------------------------------

inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream) : gen_(splitmix64(seed ^ splitmix64(stream))) {}
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(gen_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n) (n > 0); the modulo bias is below 2^-50 for the small n used here.
  int below(int n) { return static_cast<int>(gen_() % static_cast<std::uint64_t>(n)); }
  // Standard normal (Box-Muller; one value per call, the second one is discarded).
  double gaussian() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }

 private:
  std::mt19937_64 gen_;
};

// A smooth random curve in [-1, 1]: a sum of a few sinusoids with random frequencies in
// [lo_hz, hi_hz] and random phases.
class SmoothNoise {
 public:
  SmoothNoise(Rng& rng, double lo_hz, double hi_hz, int parts = 3) {
    double total = 0;
    for (int i = 0; i < parts; ++i) {
      Part p;
      p.omega = 2.0 * kPi * rng.uniform(lo_hz, hi_hz);
      p.phase = rng.uniform(0.0, 2.0 * kPi);
      p.amp = rng.uniform(0.5, 1.0);
      total += p.amp;
      parts_.push_back(p);
    }
    for (Part& p : parts_) p.amp /= total;
  }
  double operator()(double t) const {
    double v = 0;
    for (const Part& p : parts_) v += p.amp * std::sin(p.omega * t + p.phase);
    return v;
  }

 private:
  struct Part {
    double omega, phase, amp;
  };
  std::vector<Part> parts_;
};

// ---- Curves ----------------------------------------------------------------------------------

// Times on the whole millisecond, as the transcript prints them.
inline double round_ms(double t) { return std::round(t * 1000.0) / 1000.0; }

// Raised-cosine bump: 1 at `center`, 0 at |t - center| >= width / 2, C1-smooth.
inline double bump(double t, double center, double width) {
  const double x = (t - center) / (0.5 * width);
  if (x <= -1.0 || x >= 1.0) return 0.0;
  return 0.5 * (1.0 + std::cos(kPi * x));
}

// Half-cosine ramp from 0 at t0 to 1 at t1.
inline double ramp(double t, double t0, double t1) {
  if (t <= t0) return 0.0;
  if (t >= t1) return 1.0;
  return 0.5 * (1.0 - std::cos(kPi * (t - t0) / (t1 - t0)));
}

// ---- Sentences ---------------------------------------------------------------------------------

// One word of a sentence of the grammar (synth_sentences.cpp).
struct SentenceWord {
  std::string text;                           // as the transcript writes it: "The", "garden,", "house."
  int syllables = 1;                          // >= 1
  int stress = -1;                            // the stressed syllable; -1 for none (function words)
  SynthGesture gesture = SynthGesture::None;  // not None: a keyword of assets/keywords.txt
  bool pause_after = false;                   // a comma: a short pause follows, inside the sentence
};

// A sentence drawn from the grammar's templates, 4 to 10 words.
std::vector<SentenceWord> make_sentence(Rng& rng);

// Every word the grammar can say (lower case, as in its tables) with the gesture it carries.
struct GrammarWord {
  std::string text;
  SynthGesture gesture = SynthGesture::None;
};
std::vector<GrammarWord> grammar_vocabulary();

// ---- The speech plan ---------------------------------------------------------------------------

// What is said when: the ground truth behind the audio, the transcript and the gestures.
struct SpeechPlan {
  std::vector<text::Word> words;
  std::vector<SynthGesture> word_gesture;  // per word: the keyword's gesture, None for other words
  std::vector<SynthSyllable> syllables;
  std::vector<SynthPhrase> phrases;
  std::vector<double> keyword_times;
  std::vector<SynthGesture> keyword_gestures;  // per keyword time
};

// ---- The standing body (synth_stance.cpp) ------------------------------------------------------

// Where the weight is at each frame: +1 on the left leg, -1 on the right, 0 on both; it stays a
// few seconds, then moves smoothly to another of the three.
std::vector<double> weight_curve(double fps, std::size_t frame_count, Rng& rng);

// One leg's joints and its planted foot.
struct LegJoints {
  int upleg = -1, leg = -1, foot = -1;
  glm::dvec3 hip_offset{0.0};         // the hip joint from the root (cm)
  double thigh = 0, shin = 0;         // bone lengths (cm)
  glm::dvec3 ankle{0.0};              // where the ankle stays (world, cm)
  glm::dquat foot_world{1, 0, 0, 0};  // the foot's world rotation: flat, turned out
};

struct LowerBody {
  int hips = -1;
  LegJoints legs[2];  // [0] left, [1] right
};

// The legs of a skeleton with Hips, *UpLeg, *Leg, *Foot and *ToeBase (gmg::Error otherwise).
LowerBody lower_body(const Skeleton& sk);

// The lower body's inputs at one frame.
struct StancePose {
  double weight = 0;      // as weight_curve
  double shift_x = 0;     // the hips' sideways position (cm, +X the left)
  double shift_z = 0;     // the hips' forward position (cm)
  double yaw_deg = 0;     // the hips' turn about the vertical
  double bend_noise = 0;  // degrees added to both knees' bend
};

// Sets the root's position and rotation and both legs' rotations at frame f: each knee bent by
// 6-17 degrees (+ bend_noise) by the weight, the feet where b plants them. Returns the pelvis'
// roll (degrees about the forward axis; > 0 when the left hip is higher).
double pose_lower_body(Motion& m, int f, const LowerBody& b, const StancePose& p);

// ---- Steps -------------------------------------------------------------------------------------

// A lead-in silence, then sentences until `duration` (see synth.h). style in [0, 1].
SpeechPlan plan_speech(double duration, double style, Rng& rng);

// The speech of the plan: one voiced burst per syllable over background noise, sample_count
// samples at spec.sample_rate, on the PCM16 grid.
audio::Audio synth_audio(const SpeechPlan& plan, const SynthSpec& spec, std::size_t sample_count, Rng& rng);

// The gestures of the plan: frame_count frames at spec.fps on synth_skeleton(spec.joint_count_hint).
Motion synth_motion(const SpeechPlan& plan, const SynthSpec& spec, int frame_count, Rng& rng);

}  // namespace gmg::synth_internal
