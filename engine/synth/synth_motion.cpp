// The gestures of the synthetic speaker (see synth.h): curves over time (speaking envelope,
// beats, nods, emphasis, idle noise), then a pose per frame from them.
#include <algorithm>
#include <string>
#include <utility>

#include "engine/synth/synth_internal.h"

namespace gmg::synth_internal {
namespace {

glm::dquat rx(double deg) { return glm::angleAxis(deg * kDegToRad, glm::dvec3(1, 0, 0)); }
glm::dquat ry(double deg) { return glm::angleAxis(deg * kDegToRad, glm::dvec3(0, 1, 0)); }
glm::dquat rz(double deg) { return glm::angleAxis(deg * kDegToRad, glm::dvec3(0, 0, 1)); }

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

// The speaker's style (SynthSpec::style): amplitudes, tempo and poses, angles in degrees.
struct Style {
  double gain, beat_width, other_hand, talk_down, talk_fwd, talk_flex;
  double rest_down = 78.0, rest_fwd = 15.0, rest_flex = 55.0;

  explicit Style(double style)
      : gain(0.85 + 0.2 * style),         // gesture amplitude
        beat_width(0.36 - 0.04 * style),  // beat stroke duration (s)
        other_hand(0.50 + 0.30 * style),  // share of the non-dominant hand in beats
        talk_down(62.0 - 8.0 * style),    // gesture space height (upper-arm elevation)
        talk_fwd(25.0 + 6.0 * style),
        talk_flex(85.0 + 5.0 * style) {}
};

// Speaking envelope S: 0 = hands at rest, 1 = hands in the gesture space. It rises before the
// first phrase (preparation) and falls after the last one (retraction); in every pause between
// phrases the hands sink part of the way back towards rest (deeper in longer pauses), slowly
// enough that pauses stay calmer than the beats.
std::vector<double> speaking_envelope(const SpeechPlan& plan, double fps, std::size_t F) {
  std::vector<double> speak(F, 0.0);
  if (plan.phrases.empty()) return speak;
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
  return speak;
}

// Per-frame strengths of the gestures tied to the speech, each softly capped in [0, ~1].
struct GestureCurves {
  std::vector<double> beat, beat_other, nod, jaw, emph;
};

GestureCurves gesture_curves(const SpeechPlan& plan, double fps, std::size_t F, const Style& style, Rng& rng) {
  GestureCurves g{std::vector<double>(F, 0.0), std::vector<double>(F, 0.0), std::vector<double>(F, 0.0),
                  std::vector<double>(F, 0.0), std::vector<double>(F, 0.0)};
  // Beats on stressed syllables, nods with them, jaw with every syllable.
  for (std::size_t i = 0; i < plan.syllables.size(); ++i) {
    const SynthSyllable& syl = plan.syllables[i];
    add_bump(g.jaw, fps, syl.time + 0.06, 0.2, syl.stressed ? 1.0 : 0.6);
    if (!syl.stressed) continue;
    // On a keyword the emphasis gesture below replaces the beat (and the nod stays).
    const bool on_keyword = plan.word_is_keyword[static_cast<std::size_t>(syl.word)];
    add_bump(g.nod, fps, syl.time + 0.04, 0.4, rng.uniform(0.5, 1.0));
    if (on_keyword) continue;
    const double a = rng.uniform(0.7, 1.15);
    const double w = style.beat_width * rng.uniform(0.9, 1.1);
    add_bump(g.beat, fps, syl.time + 0.02, w, a);
    add_bump(g.beat_other, fps, syl.time + 0.03, w * 1.1, a * rng.uniform(0.6, 1.0));
  }
  // Emphasis gestures on keywords: preparation from 0.2 s before the keyword, stroke (apex) just
  // after its start, a slower retraction.
  for (double kt : plan.keyword_times) {
    const double apex = kt + rng.uniform(0.15, 0.25);
    // The amplitude is drawn before the retraction: the order GCC gave the two draws when they
    // were arguments of one call, fixed here so every compiler writes the same clips.
    const double amplitude = rng.uniform(0.8, 1.1);
    const double end = apex + rng.uniform(0.5, 0.7);
    add_bump2(g.emph, fps, kt - 0.2, apex, end, amplitude);
  }
  // Soft cap, so overlapping gestures do not add up without bound (smooth: tanh).
  for (double& e : g.emph) e = std::tanh(e) / std::tanh(1.0);
  for (double& b : g.beat) b = std::tanh(b) / std::tanh(1.0);
  for (double& b : g.beat_other) b = std::tanh(b) / std::tanh(1.0);
  for (double& b : g.nod) b = std::tanh(b) / std::tanh(1.0);
  for (double& b : g.jaw) b = std::tanh(b);
  return g;
}

// Slow idle curves, drawn in this order (members are initialised in declaration order).
struct IdleCurves {
  SmoothNoise sway_x, sway_z, hip_yaw;
  SmoothNoise spine_yaw, spine_roll, head_yaw, head_pitch, head_roll;
  double breath_hz, breath_phase;
  SmoothNoise arm_down[2], arm_fwd[2], arm_flex[2], curl[2];  // per side

  explicit IdleCurves(Rng& rng)
      : sway_x(rng, 0.05, 0.15),
        sway_z(rng, 0.05, 0.15),
        hip_yaw(rng, 0.03, 0.1),
        spine_yaw(rng, 0.05, 0.2),
        spine_roll(rng, 0.05, 0.2),
        head_yaw(rng, 0.05, 0.15),
        head_pitch(rng, 0.05, 0.2),
        head_roll(rng, 0.05, 0.15),
        breath_hz(rng.uniform(0.2, 0.3)),
        breath_phase(rng.uniform(0.0, 2.0 * kPi)),
        arm_down{SmoothNoise(rng, 0.1, 0.5), SmoothNoise(rng, 0.1, 0.5)},
        arm_fwd{SmoothNoise(rng, 0.1, 0.5), SmoothNoise(rng, 0.1, 0.5)},
        arm_flex{SmoothNoise(rng, 0.1, 0.6), SmoothNoise(rng, 0.1, 0.6)},
        curl{SmoothNoise(rng, 0.05, 0.3), SmoothNoise(rng, 0.05, 0.3)} {}
};

// Joint indices of the skeleton (-1 for a joint it does not have); [0] left, [1] right.
struct Joints {
  int hips, spine, spine1, spine2, neck, head, jaw;
  int shoulder[2], arm[2], fore[2], hand[2], upleg[2];
  std::vector<std::pair<int, int>> fingers[2];  // (joint, finger index 0..4)

  explicit Joints(const Skeleton& sk)
      : hips(sk.find("Hips")),
        spine(sk.find("Spine")),
        spine1(sk.find("Spine1")),
        spine2(sk.find("Spine2")),
        neck(sk.find("Neck")),
        head(sk.find("Head")),
        jaw(sk.find("Jaw")) {
    for (int side = 0; side < 2; ++side) {
      const std::string p = side == 0 ? "Left" : "Right";
      shoulder[side] = sk.find(p + "Shoulder");
      arm[side] = sk.find(p + "Arm");
      fore[side] = sk.find(p + "ForeArm");
      hand[side] = sk.find(p + "Hand");
      upleg[side] = sk.find(p + "UpLeg");
      for (int f = 0; f < 5; ++f)
        for (int level = 1; level <= 4; ++level) {
          const int j = sk.find(p + "Hand" + kFingers[f] + std::to_string(level));
          if (j >= 0) fingers[side].push_back({j, f});
        }
    }
  }
};

// Everything a frame's pose is made from.
struct PoseInputs {
  const Style& style;
  const GestureCurves& gestures;
  const std::vector<double>& speak;
  const IdleCurves& idle;
  const Joints& joints;
};

// Sets joint's rotation at frame f (joints the skeleton lacks are skipped).
void set_rotation(Motion& m, int f, int joint, const glm::dquat& q) {
  if (joint >= 0) m.rotations[m.index(f, joint)] = glm::normalize(q);
}

// Hips, legs, spine, neck, head and jaw at frame f.
void pose_trunk(Motion& m, int f, double t, const PoseInputs& in) {
  const auto fi = static_cast<std::size_t>(f);
  const Joints& J = in.joints;
  const IdleCurves& idle = in.idle;
  const double S = in.speak[fi], E = in.gestures.emph[fi];
  const double breath = std::sin(2.0 * kPi * idle.breath_hz * t + idle.breath_phase);

  // Hips: sway and a little yaw; the legs counter-rotate so the feet stay put.
  m.translations[m.index(f, J.hips)] =
      glm::dvec3(1.2 * idle.sway_x(t), 95.0 + 0.2 * breath, 0.8 * idle.sway_z(t) + 0.6 * S);
  const glm::dquat hip_q = ry(2.0 * idle.hip_yaw(t));
  set_rotation(m, f, J.hips, hip_q);
  for (int side = 0; side < 2; ++side) set_rotation(m, f, J.upleg[side], glm::inverse(hip_q));

  // Spine: breathing, sway, leaning in while speaking, a twist with the dominant hand's beats.
  const double yaw = 3.0 * idle.spine_yaw(t) - 2.0 * in.gestures.beat[fi] * in.style.gain * S;
  const double roll = 1.5 * idle.spine_roll(t);
  const double pitch = 0.8 * breath + 2.0 * S + 1.5 * E;
  set_rotation(m, f, J.spine, ry(yaw * 0.3) * rx(pitch * 0.3) * rz(roll * 0.3));
  set_rotation(m, f, J.spine1, ry(yaw * 0.35) * rx(pitch * 0.35) * rz(roll * 0.35));
  set_rotation(m, f, J.spine2, ry(yaw * 0.35) * rx(pitch * 0.35 - 1.0 * E) * rz(roll * 0.35));
  // Neck and head: slow look-around, nods on stresses, a lift on emphasis.
  const double h_pitch = 3.0 * idle.head_pitch(t) + 4.0 * in.gestures.nod[fi] * S - 3.0 * E;
  set_rotation(m, f, J.neck, ry(3.0 * idle.head_yaw(t)) * rx(0.4 * h_pitch));
  set_rotation(m, f, J.head, ry(6.0 * idle.head_yaw(t)) * rx(0.6 * h_pitch) * rz(3.0 * idle.head_roll(t)));
  set_rotation(m, f, J.jaw, rx(8.0 * in.gestures.jaw[fi]));
}

// One arm (shoulder to fingers) at frame f; side 0 left, 1 right.
void pose_arm(Motion& m, int f, double t, int side, const PoseInputs& in) {
  const auto fi = static_cast<std::size_t>(f);
  const Style& st = in.style;
  const Joints& J = in.joints;
  const IdleCurves& idle = in.idle;
  const double S = in.speak[fi], E = in.gestures.emph[fi];
  const double s = side == 0 ? 1.0 : -1.0;  // mirror: rotations about Y and Z flip sign
  const bool dominant = side == 1;          // the right hand leads the beats
  const double b = (dominant ? in.gestures.beat[fi] : st.other_hand * in.gestures.beat_other[fi]) * st.gain;
  const double lower = dominant ? 0.0 : 4.0;  // the other hand sits a little lower
  double down = st.rest_down + S * (st.talk_down + lower - st.rest_down) + 4.0 * S * idle.arm_down[side](t);
  double fwd = st.rest_fwd + S * (st.talk_fwd - st.rest_fwd) + 5.0 * S * idle.arm_fwd[side](t);
  double flex = st.rest_flex + S * (st.talk_flex - lower - st.rest_flex) + 8.0 * S * idle.arm_flex[side](t);
  double wrist = 5.0 * S;
  // Beat: the forearm and hand drop and come back up.
  flex -= 11.0 * b;
  down += 2.0 * b;
  wrist -= 12.0 * b;
  // Emphasis: both arms rise and open out to the sides, the forearms extend.
  down -= 12.0 * st.gain * E;
  fwd -= 14.0 * st.gain * E;
  flex -= 18.0 * st.gain * E;
  wrist += 10.0 * st.gain * E;
  set_rotation(m, f, J.shoulder[side], rz(s * (4.0 * st.gain * E + 1.0 * b)));
  // Upper arm: elevation `down` from the T-pose, then swung forward by `fwd` about vertical.
  set_rotation(m, f, J.arm[side], ry(-s * fwd) * rz(-s * down));
  set_rotation(m, f, J.fore[side], ry(-s * flex));
  set_rotation(m, f, J.hand[side], ry(-s * wrist) * rz(-s * 5.0 * idle.curl[side](t)));
  // Fingers: a relaxed curl that varies slowly and opens on emphasis.
  const double c = 15.0 + 8.0 * idle.curl[side](t) - 12.0 * E;
  for (const auto& [j, finger] : J.fingers[side]) {
    if (finger == 4)
      set_rotation(m, f, j, ry(s * 0.5 * c) * rz(-s * 0.3 * c));
    else
      set_rotation(m, f, j, rz(-s * c * (1.0 + 0.1 * finger)));
  }
}

}  // namespace

Motion synth_motion(const SpeechPlan& plan, const SynthSpec& spec, int frame_count, Rng& rng) {
  const Skeleton sk = synth_skeleton(spec.joint_count_hint);
  Motion m = motion_rest(sk, spec.fps, frame_count);
  const double fps = spec.fps;
  const auto F = static_cast<std::size_t>(frame_count);
  const Style style(spec.style);
  const std::vector<double> speak = speaking_envelope(plan, fps, F);
  const GestureCurves gestures = gesture_curves(plan, fps, F, style, rng);
  const IdleCurves idle(rng);
  const Joints joints(sk);
  const PoseInputs in{style, gestures, speak, idle, joints};
  for (int f = 0; f < frame_count; ++f) {
    const double t = f / fps;
    pose_trunk(m, f, t, in);
    for (int side = 0; side < 2; ++side) pose_arm(m, f, t, side, in);
  }
  return m;
}

}  // namespace gmg::synth_internal
