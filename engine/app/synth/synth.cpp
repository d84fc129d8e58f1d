// Procedural synthetic speaker (see synth.h for what is generated and why).
//
// Determinism: every random number comes from std::mt19937_64 through the helpers of class Rng
// below (never std::uniform_*_distribution, whose output is implementation-defined). The speech
// plan, the audio noise and the motion each have their own generator, seeded from the spec's
// seed, so e.g. a change in how the audio is drawn never changes the motion.
#include "engine/app/synth/synth.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <locale>
#include <ostream>
#include <random>
#include <sstream>

#include "engine/motion/bvh.h"
#include "engine/core/error.h"
#include "engine/core/files.h"

namespace gmg {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr int kMaxJoints = 1000;

// ---------------------------------------------------------------------------------------------
// Randomness

std::uint64_t splitmix64(std::uint64_t x) {
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
  bool chance(double p) { return uniform() < p; }
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

double round_ms(double t) { return std::round(t * 1000.0) / 1000.0; }

// Raised-cosine bump: 1 at `center`, 0 at |t - center| >= width / 2, C1-smooth.
double bump(double t, double center, double width) {
  const double x = (t - center) / (0.5 * width);
  if (x <= -1.0 || x >= 1.0) return 0.0;
  return 0.5 * (1.0 + std::cos(kPi * x));
}

// Half-cosine ramp from 0 at t0 to 1 at t1.
double ramp(double t, double t0, double t1) {
  if (t <= t0) return 0.0;
  if (t >= t1) return 1.0;
  return 0.5 * (1.0 - std::cos(kPi * (t - t0) / (t1 - t0)));
}

// ---------------------------------------------------------------------------------------------
// Skeleton

struct Node {
  std::string name;
  int parent = -1;
  glm::dvec3 offset{0.0};
  glm::dvec3 tip{0.0};  // End Site offset when the node ends up a leaf
  std::vector<int> children;
};

struct Tree {
  std::vector<Node> nodes;
  int add(const std::string& name, int parent, glm::dvec3 offset, glm::dvec3 tip) {
    Node n;
    n.name = name;
    n.parent = parent;
    n.offset = offset;
    n.tip = tip;
    nodes.push_back(n);
    const int id = static_cast<int>(nodes.size()) - 1;
    if (parent >= 0) nodes[static_cast<std::size_t>(parent)].children.push_back(id);
    return id;
  }
  int find(const std::string& name) const {
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].name == name) return static_cast<int>(i);
    return -1;
  }
};

void flatten(const Tree& tree, int node, int parent_index, Skeleton& out) {
  const Node& n = tree.nodes[static_cast<std::size_t>(node)];
  Joint j;
  j.name = n.name;
  j.parent = parent_index;
  j.offset = n.offset;
  j.rotation_order = {2, 0, 1};
  if (parent_index < 0)
    j.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition,
                  Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  else
    j.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  j.has_end_site = n.children.empty();
  if (j.has_end_site) j.end_site = n.tip;
  out.joints.push_back(j);
  const int me = out.joint_count() - 1;
  for (int c : n.children) flatten(tree, c, me, out);
}

const char* const kFingers[5] = {"Index", "Middle", "Ring", "Pinky", "Thumb"};

}  // namespace

Skeleton synth_skeleton(int joint_count_hint) {
  if (joint_count_hint < 0 || joint_count_hint > kMaxJoints)
    throw Error("synth_skeleton: joint_count_hint " + std::to_string(joint_count_hint) +
                " outside 0.." + std::to_string(kMaxJoints));
  Tree t;
  using V = glm::dvec3;
  const int hips = t.add("Hips", -1, V(0, 95, 0), V(0, 10, 0));
  const int spine = t.add("Spine", hips, V(0, 10, 0), V(0, 12, 0));
  const int spine1 = t.add("Spine1", spine, V(0, 12, 0), V(0, 12, 0));
  const int spine2 = t.add("Spine2", spine1, V(0, 12, 0), V(0, 12, 0));
  const int neck = t.add("Neck", spine2, V(0, 16, 0), V(0, 10, 0));
  t.add("Head", neck, V(0, 10, 0), V(0, 18, 0));
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? 1.0 : -1.0;  // Left is +X (the character faces +Z)
    const std::string p = side == 0 ? "Left" : "Right";
    const int sh = t.add(p + "Shoulder", spine2, V(3 * s, 10, 0), V(14 * s, 0, 0));
    const int arm = t.add(p + "Arm", sh, V(14 * s, 0, 0), V(28 * s, 0, 0));
    const int fore = t.add(p + "ForeArm", arm, V(28 * s, 0, 0), V(25 * s, 0, 0));
    t.add(p + "Hand", fore, V(25 * s, 0, 0), V(18 * s, 0, 0));
  }
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? 1.0 : -1.0;
    const std::string p = side == 0 ? "Left" : "Right";
    const int up = t.add(p + "UpLeg", hips, V(9 * s, -5, 0), V(0, -42, 0));
    const int leg = t.add(p + "Leg", up, V(0, -42, 0), V(0, -42, 0));
    const int foot = t.add(p + "Foot", leg, V(0, -42, 0), V(0, -6, 13));
    t.add(p + "ToeBase", foot, V(0, -6, 13), V(0, 0, 6));
  }
  const int want = std::max(joint_count_hint, static_cast<int>(t.nodes.size()));

  // Finger chains, one segment level at a time (so a hint in between gives every finger of
  // both hands the same depth where possible), then face joints, then an accessory chain.
  const double seg_len[4] = {4.0, 2.6, 2.0, 1.6};
  for (int level = 0; level < 4; ++level) {
    for (int f = 0; f < 5; ++f) {
      for (int side = 1; side >= 0; --side) {  // Right first: it is the dominant hand
        if (static_cast<int>(t.nodes.size()) >= want) break;
        const double s = side == 0 ? 1.0 : -1.0;
        const std::string p = side == 0 ? "Left" : "Right";
        const std::string name = p + "Hand" + kFingers[f] + std::to_string(level + 1);
        // Finger direction in the hand's frame (hand along +-X, palm down, thumb forward).
        const V dir = f == 4 ? glm::normalize(V(0.6 * s, -0.2, 0.8)) : V(s, 0, 0);
        const int parent = level == 0 ? t.find(p + "Hand")
                                      : t.find(p + "Hand" + kFingers[f] + std::to_string(level));
        V offset;
        if (level == 0) {
          const double z[5] = {2.5, 0.7, -1.1, -2.8, 2.8};
          const double x[5] = {9.0, 9.2, 8.8, 8.2, 2.5};
          offset = V(x[f] * s, f == 4 ? -1.0 : 0.0, z[f]);
        } else {
          offset = dir * seg_len[level - 1] * (f == 4 ? 0.9 : (f == 3 ? 0.8 : 1.0));
        }
        const double tip_len = level < 3 ? seg_len[level] : 1.2;
        t.add(name, parent, offset, dir * tip_len);
      }
    }
  }
  const int head = t.find("Head");
  if (static_cast<int>(t.nodes.size()) < want) t.add("Jaw", head, V(0, 2, 3), V(0, -3, 7));
  if (static_cast<int>(t.nodes.size()) < want) t.add("LeftEye", head, V(3.2, 8, 8), V(0, 0, 1.5));
  if (static_cast<int>(t.nodes.size()) < want) t.add("RightEye", head, V(-3.2, 8, 8), V(0, 0, 1.5));
  int prev = spine2;
  for (int k = 1; static_cast<int>(t.nodes.size()) < want; ++k)
    prev = t.add("Accessory" + std::to_string(k), prev, k == 1 ? V(0, 6, -10) : V(0, -3, -1.5),
                 V(0, -3, -1.5));

  Skeleton sk;
  flatten(t, hips, -1, sk);
  return sk;
}

// ---------------------------------------------------------------------------------------------
// Speech plan

namespace {

struct VocabWord {
  const char* text;
  int syllables;
  int stress;  // index of the stressed syllable, -1 for none
};

// Gesture keywords: every one of them is in assets/keywords.txt.
const VocabWord kKeywords[] = {
    {"this", 1, 0},  {"big", 1, 0},    {"not", 1, 0},    {"very", 2, 0},   {"all", 1, 0},
    {"never", 2, 0}, {"here", 1, 0},   {"really", 2, 0}, {"always", 2, 0}, {"together", 3, 1},
};
// Neutral content words: none of them is in the lexicon.
const VocabWord kContent[] = {
    {"people", 2, 0},   {"water", 2, 0},    {"music", 2, 0},  {"story", 2, 0},   {"city", 2, 0},
    {"problem", 2, 0},  {"question", 2, 0}, {"paper", 2, 0},  {"money", 2, 0},   {"garden", 2, 0},
    {"family", 3, 0},   {"computer", 3, 1}, {"animal", 3, 0}, {"energy", 3, 0},  {"company", 3, 0},
    {"banana", 3, 1},   {"house", 1, 0},    {"work", 1, 0},   {"car", 1, 0},     {"made", 1, 0},
    {"said", 1, 0},     {"book", 1, 0},     {"friend", 1, 0}, {"school", 1, 0},  {"game", 1, 0},
    {"road", 1, 0},     {"food", 1, 0},     {"world", 1, 0},  {"town", 1, 0},    {"dog", 1, 0},
};
// Unstressed function words: none of them is in the lexicon, and none starts a lexicon phrase
// together with the words above.
const VocabWord kFunction[] = {
    {"the", 1, -1}, {"and", 1, -1}, {"is", 1, -1},   {"to", 1, -1},  {"of", 1, -1},
    {"it", 1, -1},  {"was", 1, -1}, {"with", 1, -1}, {"from", 1, -1},
};
template <typename T, std::size_t N>
constexpr int count_of(const T (&)[N]) {
  return static_cast<int>(N);
}

struct Plan {
  std::vector<text::Word> words;
  std::vector<bool> word_is_keyword;
  std::vector<SynthSyllable> syllables;
  std::vector<SynthPhrase> phrases;
  std::vector<double> keyword_times;
};

Plan plan_speech(double duration, double style, Rng& rng) {
  Plan plan;
  const double end_limit = duration - 0.15;  // the last word ends at least 150 ms before the end
  double t = rng.uniform(0.4, 0.9);          // lead-in silence
  int previous_kind = 0;                     // 0 content, 1 function, 2 keyword
  while (t + 0.6 <= end_limit) {
    const double target_end = std::min(t + rng.uniform(1.5, 4.0), end_limit);
    const double rate = std::clamp(4.3 + 0.7 * style + rng.uniform(-0.25, 0.25), 4.0, 5.2);
    double cur = t;
    const std::size_t first_word = plan.words.size();
    for (;;) {
      // Pick a word: a function word ~30% (never two in a row), a keyword ~15% (never two in a
      // row, so every keyword is its own keyword event and gesture), otherwise a content word.
      const double r = rng.uniform();
      int kind;
      if (r < 0.17 && previous_kind != 2)
        kind = 2;
      else if (r < 0.17 + 0.30 && previous_kind != 1)
        kind = 1;
      else
        kind = 0;
      const VocabWord* w;
      if (kind == 2) {
        w = &kKeywords[rng.below(count_of(kKeywords))];
      } else if (kind == 1) {
        w = &kFunction[rng.below(count_of(kFunction))];
      } else {
        w = &kContent[rng.below(count_of(kContent))];
      }
      std::vector<double> lengths;
      double word_len = 0;
      for (int s = 0; s < w->syllables; ++s) {
        lengths.push_back(round_ms(rng.uniform(0.8, 1.2) / rate));
        word_len += lengths.back();
      }
      const bool have_words = plan.words.size() > first_word;
      if (cur + word_len > end_limit) break;
      if (have_words && cur + word_len > target_end) break;
      const int word_index = static_cast<int>(plan.words.size());
      double s_time = round_ms(cur);
      for (int s = 0; s < w->syllables; ++s) {
        SynthSyllable syl;
        syl.time = s_time;
        syl.stressed = s == w->stress;
        syl.word = word_index;
        plan.syllables.push_back(syl);
        s_time = round_ms(s_time + lengths[static_cast<std::size_t>(s)]);
      }
      text::Word word;
      word.start = round_ms(cur);
      word.end = std::min(round_ms(s_time - 0.02), round_ms(end_limit));  // ends as its last syllable fades
      word.text = w->text;
      plan.words.push_back(word);
      plan.word_is_keyword.push_back(kind == 2);
      if (kind == 2) plan.keyword_times.push_back(word.start);
      previous_kind = kind;
      cur = s_time + round_ms(rng.uniform(0.0, 0.03));  // short inter-word gap
    }
    if (plan.words.size() == first_word) break;
    SynthPhrase ph;
    ph.start = plan.words[first_word].start;
    ph.end = plan.words.back().end;
    plan.phrases.push_back(ph);
    previous_kind = 1;  // so the next phrase opens with a content word or a keyword
    t = ph.end + rng.uniform(0.3, 0.8);
  }
  return plan;
}

// ---------------------------------------------------------------------------------------------
// Audio

audio::Audio synth_audio(const Plan& plan, const SynthSpec& spec, std::size_t sample_count, Rng& rng) {
  audio::Audio a;
  a.sample_rate = spec.sample_rate;
  const double sr = spec.sample_rate;
  std::vector<double> x(sample_count);
  for (double& v : x) v = 1e-3 * rng.gaussian();  // background noise

  const double f0_speaker = 110.0 + 90.0 * spec.style + rng.uniform(0.0, 15.0);  // 110..215 Hz
  std::size_t phrase = 0;
  for (std::size_t i = 0; i < plan.syllables.size(); ++i) {
    const SynthSyllable& syl = plan.syllables[i];
    while (phrase + 1 < plan.phrases.size() && plan.phrases[phrase].end < syl.time) ++phrase;
    const SynthPhrase& ph = plan.phrases[phrase];
    const double progress = ph.end > ph.start ? std::clamp((syl.time - ph.start) / (ph.end - ph.start), 0.0, 1.0) : 0.0;
    const double amp = (syl.stressed ? 0.30 : 0.14) * rng.uniform(0.85, 1.15);
    const double decay = syl.stressed ? rng.uniform(0.11, 0.15) : rng.uniform(0.08, 0.11);
    const double tau = decay / 3.0;  // the burst has fallen to 5% after `decay`
    const double attack = 0.010;
    const double f0 = f0_speaker * (syl.stressed ? 1.15 : 1.0) * (1.0 - 0.12 * progress) * rng.uniform(0.96, 1.04);
    const double glide = syl.stressed ? -0.10 : -0.04;  // relative pitch change over the syllable
    const double consonant_amp = amp * rng.uniform(0.3, 0.5);
    const double consonant_len = 0.012;
    // The burst lasts until the next syllable starts (or 2.5 decays), with a 5 ms fade-out.
    double length = 0.010 + 2.5 * decay;
    if (i + 1 < plan.syllables.size()) length = std::min(length, plan.syllables[i + 1].time - syl.time);
    const double fade = 0.005;
    const int harmonics = std::max(1, std::min(10, static_cast<int>(0.45 * sr / (f0 * 1.05))));
    double norm = 0;
    for (int k = 1; k <= harmonics; ++k) norm += 1.0 / k;

    const auto first = static_cast<std::size_t>(std::llround(syl.time * sr));
    const auto n = static_cast<std::size_t>(std::llround(length * sr));
    double phase = 0;
    for (std::size_t s = 0; s < n && first + s < sample_count; ++s) {
      const double tt = static_cast<double>(s) / sr;
      double env = tt < attack ? 0.5 * (1.0 - std::cos(kPi * tt / attack)) : std::exp(-(tt - attack) / tau);
      if (tt > length - fade) env *= std::max(0.0, (length - tt) / fade);
      // Harmonics sin(k*phase) by the Chebyshev recurrence (two trig calls per sample).
      const double s1 = std::sin(phase), c1 = std::cos(phase);
      double prev = 0, curv = s1, voiced = 0;
      for (int k = 1; k <= harmonics; ++k) {
        voiced += curv / k;
        const double next = 2.0 * c1 * curv - prev;
        prev = curv;
        curv = next;
      }
      double v = amp * env * voiced / norm;
      if (tt < consonant_len) v += consonant_amp * 0.5 * (1.0 - std::cos(2.0 * kPi * tt / consonant_len)) * rng.gaussian();
      x[first + s] += v;
      const double f = f0 * (1.0 + glide * tt / length);
      phase += 2.0 * kPi * f / sr;
      if (phase > 2.0 * kPi) phase -= 2.0 * kPi;
    }
  }
  // Quantise to the PCM16 grid, so writing and reading a WAV gives back the same samples.
  a.samples.resize(sample_count);
  for (std::size_t s = 0; s < sample_count; ++s) {
    const double q = std::clamp(std::round(x[s] * 32768.0), -32768.0, 32767.0);
    a.samples[s] = static_cast<float>(q / 32768.0);
  }
  return a;
}

// ---------------------------------------------------------------------------------------------
// Motion

glm::dquat rx(double deg) { return glm::angleAxis(deg * kDeg, glm::dvec3(1, 0, 0)); }
glm::dquat ry(double deg) { return glm::angleAxis(deg * kDeg, glm::dvec3(0, 1, 0)); }
glm::dquat rz(double deg) { return glm::angleAxis(deg * kDeg, glm::dvec3(0, 0, 1)); }

// Adds amplitude * bump(t; center, width) to every frame of `curve` the bump touches.
void add_bump(std::vector<double>& curve, double fps, double center, double width, double amplitude) {
  const int n = static_cast<int>(curve.size());
  const int f0 = std::max(0, static_cast<int>(std::floor((center - 0.5 * width) * fps)));
  const int f1 = std::min(n - 1, static_cast<int>(std::ceil((center + 0.5 * width) * fps)));
  for (int f = f0; f <= f1; ++f) curve[static_cast<std::size_t>(f)] += amplitude * bump(f / fps, center, width);
}

// Adds amplitude * (a half raised cosine rising over [start, apex], then one falling over
// [apex, end]) to `curve`: an asymmetric bump, C1-smooth.
void add_bump2(std::vector<double>& curve, double fps, double start, double apex, double end, double amplitude) {
  const int n = static_cast<int>(curve.size());
  const int f0 = std::max(0, static_cast<int>(std::floor(start * fps)));
  const int f1 = std::min(n - 1, static_cast<int>(std::ceil(end * fps)));
  for (int f = f0; f <= f1; ++f) {
    const double t = f / fps;
    const double v = t < apex ? ramp(t, start, apex) : 1.0 - ramp(t, apex, end);
    curve[static_cast<std::size_t>(f)] += amplitude * v;
  }
}

Motion synth_motion(const Plan& plan, const SynthSpec& spec, int frame_count, Rng& rng) {
  const Skeleton sk = synth_skeleton(spec.joint_count_hint);
  Motion m = motion_rest(sk, spec.fps, frame_count);
  const double fps = spec.fps;
  const auto F = static_cast<std::size_t>(frame_count);
  const double style = spec.style;

  // Speaker style.
  const double gain = 0.85 + 0.2 * style;           // gesture amplitude
  const double beat_width = 0.36 - 0.04 * style;    // beat stroke duration (s)
  const double other_hand = 0.50 + 0.30 * style;    // share of the non-dominant hand in beats
  const double talk_down = 62.0 - 8.0 * style;      // gesture space height (upper-arm elevation)
  const double talk_fwd = 25.0 + 6.0 * style;
  const double talk_flex = 85.0 + 5.0 * style;
  const double rest_down = 78.0, rest_fwd = 15.0, rest_flex = 55.0;

  // Speaking envelope S: 0 = hands at rest, 1 = hands in the gesture space. It rises before the
  // first phrase (preparation) and falls after the last one (retraction); in every pause between
  // phrases the hands sink part of the way back towards rest (deeper in longer pauses), slowly
  // enough that pauses stay calmer than the beats.
  std::vector<double> speak(F, 0.0);
  if (!plan.phrases.empty()) {
    const double r0 = plan.phrases.front().start - 0.7, r1 = plan.phrases.front().start + 0.05;
    const double d0 = plan.phrases.back().end, d1 = plan.phrases.back().end + 0.8;
    for (std::size_t f = 0; f < F; ++f) {
      const double t = static_cast<double>(f) / fps;
      speak[f] = std::min(ramp(t, r0, r1), 1.0 - ramp(t, d0, d1));
    }
    std::vector<double> dip(F, 0.0);
    for (std::size_t k = 0; k + 1 < plan.phrases.size(); ++k) {
      const double a = plan.phrases[k].end, b = plan.phrases[k + 1].start;
      const double depth = 0.5 * std::clamp((b - a - 0.2) / 0.6, 0.0, 1.0);
      add_bump(dip, fps, 0.5 * (a + b), (b - a) + 0.8, depth);
    }
    for (std::size_t f = 0; f < F; ++f) speak[f] = std::max(0.0, speak[f] - dip[f]);
  }

  // Beats on stressed syllables, nods with them, jaw with every syllable.
  std::vector<double> beat(F, 0.0), beat_other(F, 0.0), nod(F, 0.0), jaw(F, 0.0);
  for (std::size_t i = 0; i < plan.syllables.size(); ++i) {
    const SynthSyllable& syl = plan.syllables[i];
    add_bump(jaw, fps, syl.time + 0.06, 0.2, syl.stressed ? 1.0 : 0.6);
    if (!syl.stressed) continue;
    // On a keyword the emphasis gesture below replaces the beat (and the nod stays).
    const bool on_keyword = plan.word_is_keyword[static_cast<std::size_t>(syl.word)];
    add_bump(nod, fps, syl.time + 0.04, 0.4, rng.uniform(0.5, 1.0));
    if (on_keyword) continue;
    const double a = rng.uniform(0.7, 1.15);
    const double w = beat_width * rng.uniform(0.9, 1.1);
    add_bump(beat, fps, syl.time + 0.02, w, a);
    add_bump(beat_other, fps, syl.time + 0.03, w * 1.1, a * rng.uniform(0.6, 1.0));
  }
  // Emphasis gestures on keywords.
  std::vector<double> emph(F, 0.0);
  // Preparation from 0.2 s before the keyword, stroke (apex) just after its start, a slower
  // retraction.
  for (double kt : plan.keyword_times) {
    const double apex = kt + rng.uniform(0.15, 0.25);
    add_bump2(emph, fps, kt - 0.2, apex, apex + rng.uniform(0.5, 0.7), rng.uniform(0.8, 1.1));
  }
  // Soft cap, so overlapping gestures do not add up without bound (smooth: tanh).
  for (double& e : emph) e = std::tanh(e) / std::tanh(1.0);
  for (double& b : beat) b = std::tanh(b) / std::tanh(1.0);
  for (double& b : beat_other) b = std::tanh(b) / std::tanh(1.0);
  for (double& b : nod) b = std::tanh(b) / std::tanh(1.0);
  for (double& b : jaw) b = std::tanh(b);

  // Slow idle curves.
  SmoothNoise sway_x(rng, 0.05, 0.15), sway_z(rng, 0.05, 0.15), hip_yaw(rng, 0.03, 0.1);
  SmoothNoise spine_yaw(rng, 0.05, 0.2), spine_roll(rng, 0.05, 0.2), head_yaw(rng, 0.05, 0.15),
      head_pitch(rng, 0.05, 0.2), head_roll(rng, 0.05, 0.15);
  const double breath_hz = rng.uniform(0.2, 0.3), breath_phase = rng.uniform(0.0, 2.0 * kPi);
  SmoothNoise arm_down[2] = {SmoothNoise(rng, 0.1, 0.5), SmoothNoise(rng, 0.1, 0.5)};
  SmoothNoise arm_fwd[2] = {SmoothNoise(rng, 0.1, 0.5), SmoothNoise(rng, 0.1, 0.5)};
  SmoothNoise arm_flex[2] = {SmoothNoise(rng, 0.1, 0.6), SmoothNoise(rng, 0.1, 0.6)};
  SmoothNoise curl[2] = {SmoothNoise(rng, 0.05, 0.3), SmoothNoise(rng, 0.05, 0.3)};

  auto J = [&sk](const std::string& name) { return sk.find(name); };
  const int hips = J("Hips"), spine = J("Spine"), spine1 = J("Spine1"), spine2 = J("Spine2");
  const int neck = J("Neck"), head = J("Head"), jaw_j = J("Jaw");
  int shoulder[2], arm[2], fore[2], hand[2], upleg[2];
  std::vector<std::pair<int, int>> fingers[2];  // (joint, finger index 0..4)
  for (int side = 0; side < 2; ++side) {
    const std::string p = side == 0 ? "Left" : "Right";
    shoulder[side] = J(p + "Shoulder");
    arm[side] = J(p + "Arm");
    fore[side] = J(p + "ForeArm");
    hand[side] = J(p + "Hand");
    upleg[side] = J(p + "UpLeg");
    for (int f = 0; f < 5; ++f)
      for (int level = 1; level <= 4; ++level) {
        const int j = J(p + "Hand" + kFingers[f] + std::to_string(level));
        if (j >= 0) fingers[side].push_back({j, f});
      }
  }

  for (int f = 0; f < frame_count; ++f) {
    const auto fi = static_cast<std::size_t>(f);
    const double t = f / fps;
    const double S = speak[fi], E = emph[fi];
    auto set = [&m, f](int joint, const glm::dquat& q) {
      if (joint >= 0) m.rotations[m.index(f, joint)] = glm::normalize(q);
    };
    const double breath = std::sin(2.0 * kPi * breath_hz * t + breath_phase);

    // Hips: sway and a little yaw; the legs counter-rotate so the feet stay put.
    m.translations[m.index(f, hips)] =
        glm::dvec3(1.2 * sway_x(t), 95.0 + 0.2 * breath, 0.8 * sway_z(t) + 0.6 * S);
    const glm::dquat hip_q = ry(2.0 * hip_yaw(t));
    set(hips, hip_q);
    for (int side = 0; side < 2; ++side) set(upleg[side], glm::inverse(hip_q));

    // Spine: breathing, sway, leaning in while speaking, a twist with the dominant hand's beats.
    const double yaw = 3.0 * spine_yaw(t) - 2.0 * beat[fi] * gain * S;
    const double roll = 1.5 * spine_roll(t);
    const double pitch = 0.8 * breath + 2.0 * S + 1.5 * E;
    set(spine, ry(yaw * 0.3) * rx(pitch * 0.3) * rz(roll * 0.3));
    set(spine1, ry(yaw * 0.35) * rx(pitch * 0.35) * rz(roll * 0.35));
    set(spine2, ry(yaw * 0.35) * rx(pitch * 0.35 - 1.0 * E) * rz(roll * 0.35));
    // Neck and head: slow look-around, nods on stresses, a lift on emphasis.
    const double h_pitch = 3.0 * head_pitch(t) + 4.0 * nod[fi] * S - 3.0 * E;
    set(neck, ry(3.0 * head_yaw(t)) * rx(0.4 * h_pitch));
    set(head, ry(6.0 * head_yaw(t)) * rx(0.6 * h_pitch) * rz(3.0 * head_roll(t)));
    set(jaw_j, rx(8.0 * jaw[fi]));

    for (int side = 0; side < 2; ++side) {
      const double s = side == 0 ? 1.0 : -1.0;  // mirror: rotations about Y and Z flip sign
      const bool dominant = side == 1;            // the right hand leads the beats
      const double b = (dominant ? beat[fi] : other_hand * beat_other[fi]) * gain;
      const double lower = dominant ? 0.0 : 4.0;  // the other hand sits a little lower
      double down = rest_down + S * (talk_down + lower - rest_down) + 4.0 * S * arm_down[side](t);
      double fwd = rest_fwd + S * (talk_fwd - rest_fwd) + 5.0 * S * arm_fwd[side](t);
      double flex = rest_flex + S * (talk_flex - lower - rest_flex) + 8.0 * S * arm_flex[side](t);
      double wrist = 5.0 * S;
      // Beat: the forearm and hand drop and come back up.
      flex -= 11.0 * b;
      down += 2.0 * b;
      wrist -= 12.0 * b;
      // Emphasis: both arms rise and open out to the sides, the forearms extend.
      down -= 12.0 * gain * E;
      fwd -= 14.0 * gain * E;
      flex -= 18.0 * gain * E;
      wrist += 10.0 * gain * E;
      set(shoulder[side], rz(s * (4.0 * gain * E + 1.0 * b)));
      // Upper arm: elevation `down` from the T-pose, then swung forward by `fwd` about vertical.
      set(arm[side], ry(-s * fwd) * rz(-s * down));
      set(fore[side], ry(-s * flex));
      set(hand[side], ry(-s * wrist) * rz(-s * 5.0 * curl[side](t)));
      // Fingers: a relaxed curl that varies slowly and opens on emphasis.
      const double c = 15.0 + 8.0 * curl[side](t) - 12.0 * E;
      for (const auto& [j, finger] : fingers[side]) {
        if (finger == 4)
          set(j, ry(s * 0.5 * c) * rz(-s * 0.3 * c));
        else
          set(j, rz(-s * c * (1.0 + 0.1 * finger)));
      }
    }
  }
  return m;
}

void check_spec(const SynthSpec& spec) {
  auto bad = [](const std::string& what) { throw Error("synth_speaker: " + what); };
  if (!std::isfinite(spec.duration_s) || spec.duration_s <= 0) bad("duration_s must be a positive number");
  if (!std::isfinite(spec.fps) || spec.fps <= 0) bad("fps must be a positive number");
  if (spec.sample_rate < 8000) bad("sample_rate must be at least 8000");
  if (!(spec.style >= 0.0 && spec.style <= 1.0)) bad("style must lie in [0, 1]");
  if (spec.duration_s * spec.fps > 1e8) bad("clip too long (more than 10^8 frames)");
  if (spec.duration_s * spec.sample_rate > 1e9) bad("clip too long (more than 10^9 samples)");
}

}  // namespace

SynthClip synth_speaker(const SynthSpec& spec) {
  check_spec(spec);
  (void)synth_skeleton(spec.joint_count_hint);  // validates the hint before any work
  const int frame_count = static_cast<int>(std::llround(spec.duration_s * spec.fps));
  const auto sample_count = static_cast<std::size_t>(std::llround(spec.duration_s * spec.sample_rate));

  Rng plan_rng(spec.seed, 1), audio_rng(spec.seed, 2), motion_rng(spec.seed, 3);
  Plan plan = plan_speech(spec.duration_s, spec.style, plan_rng);

  SynthClip clip;
  clip.motion = synth_motion(plan, spec, frame_count, motion_rng);
  clip.audio = synth_audio(plan, spec, sample_count, audio_rng);
  clip.words = std::move(plan.words);
  clip.syllables = std::move(plan.syllables);
  clip.phrases = std::move(plan.phrases);
  clip.keyword_times = std::move(plan.keyword_times);
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
