// The gestures of the synthetic speaker (see synth.h): curves over time (speaking envelope,
// beats, nods, emphasis gestures, weight shifts, idle noise), then a pose per frame from them.
// The lower body is posed by synth_stance.cpp.
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

// An arm's pose, in degrees. The upper arm hangs, then is raised forward (flexion) and out to the
// side (abduction) and turned about its length (twist > 0 turns the forearm in across the body);
// the elbow bends the forearm forward; the wrist bends the hand towards the palm (> 0).
struct ArmPose {
  double flexion = 0, abduction = 0, twist = 0, elbow = 0, wrist = 0;
};

ArmPose mix(const ArmPose& a, const ArmPose& b, double t) {
  return ArmPose{a.flexion + t * (b.flexion - a.flexion), a.abduction + t * (b.abduction - a.abduction),
                 a.twist + t * (b.twist - a.twist), a.elbow + t * (b.elbow - a.elbow),
                 a.wrist + t * (b.wrist - a.wrist)};
}

// Adds k times d to p.
void add(ArmPose& p, const ArmPose& d, double k) {
  p.flexion += k * d.flexion;
  p.abduction += k * d.abduction;
  p.twist += k * d.twist;
  p.elbow += k * d.elbow;
  p.wrist += k * d.wrist;
}

// The speaker's style (SynthSpec::style): amplitudes, tempo and the hands' place while talking.
struct Style {
  double gain, beat_width, other_hand;
  ArmPose rest{6.0, 7.0, 8.0, 14.0, 4.0};  // hands hanging beside the thighs
  ArmPose talk;                            // hands in front of the belly, forearms forward

  explicit Style(double style)
      : gain(0.9 + 0.25 * style),         // gesture amplitude
        beat_width(0.40 - 0.04 * style),  // beat stroke duration (s)
        other_hand(0.45 + 0.30 * style),  // share of the non-dominant hand in beats
        talk{42.0 + 6.0 * style, 16.0 + 4.0 * style, 24.0, 86.0 + 6.0 * style, -8.0} {}
};

// What a unit of each gesture curve adds to the dominant arm (the other arm: see pose_arm).
const ArmPose kBeat{-2.0, 1.0, 0.0, -17.0, 12.0};       // the stroke: forearm and hand drop
const ArmPose kBeatLift{2.0, 0.0, 0.0, 10.0, -8.0};     // before it: a small lift
const ArmPose kOpen{4.0, 26.0, -34.0, -30.0, -16.0};    // both hands open out to the sides
const ArmPose kPoint{30.0, 18.0, -20.0, -46.0, -6.0};   // the arm reaches forward and points
const ArmPose kSweepIn{2.0, -6.0, 16.0, 6.0, 0.0};      // hands gather in front...
const ArmPose kSweep{-4.0, 30.0, -34.0, -12.0, -12.0};  // ...then sweep out, palms down
const ArmPose kLift{12.0, 4.0, 10.0, 20.0, -6.0};       // both hands come up to the chest

// Speaking envelope S: 0 = hands at rest, 1 = hands in the gesture space. For each sentence it
// rises in the 0.85 s before the first word (preparation) and falls in the 0.8 s after the last
// one (retraction); between sentences the hands reach rest, or nearly, before rising again. At a
// comma they sink a little. The sentences' envelopes u combine as 1 - prod(1 - u), which is
// smooth where a retraction meets the next preparation (a maximum would turn back abruptly).
std::vector<double> speaking_envelope(const SpeechPlan& plan, double fps, std::size_t F) {
  std::vector<double> still(F, 1.0);  // 1 - S
  std::size_t first = 0;
  for (std::size_t k = 0; k < plan.phrases.size(); ++k) {
    if (!plan.phrases[k].ends_sentence) continue;
    const double a = plan.phrases[first].start, b = plan.phrases[k].end;
    const int f0 = std::max(0, static_cast<int>(std::floor((a - 0.9) * fps)));
    const int f1 = std::min(static_cast<int>(F) - 1, static_cast<int>(std::ceil((b + 0.9) * fps)));
    for (int f = f0; f <= f1; ++f) {
      const double t = f / fps;
      still[static_cast<std::size_t>(f)] *= 1.0 - ramp(t, a - 0.9, a - 0.05) * (1.0 - ramp(t, b + 0.1, b + 0.9));
    }
    first = k + 1;
  }
  std::vector<double> speak(F);
  for (std::size_t f = 0; f < F; ++f) speak[f] = 1.0 - still[f];
  std::vector<double> dip(F, 0.0);
  for (std::size_t k = 0; k + 1 < plan.phrases.size(); ++k) {
    if (plan.phrases[k].ends_sentence) continue;
    const double a = plan.phrases[k].end, b = plan.phrases[k + 1].start;
    add_bump(dip, fps, 0.5 * (a + b), (b - a) + 0.3, 0.2);
  }
  for (std::size_t f = 0; f < F; ++f) speak[f] = std::max(0.0, speak[f] - dip[f]);
  return speak;
}

// Per-frame strengths of the gestures tied to the speech, each softly capped in [0, ~1].
struct GestureCurves {
  std::vector<double> beat, beat_lift, beat_other, nod, jaw, sweep_in;
  std::vector<double> emphasis[5];  // by SynthGesture (index 0, None, unused)
};

GestureCurves gesture_curves(const SpeechPlan& plan, double fps, std::size_t F, const Style& style, Rng& rng) {
  GestureCurves g;
  for (std::vector<double>* c : {&g.beat, &g.beat_lift, &g.beat_other, &g.nod, &g.jaw, &g.sweep_in}) c->assign(F, 0.0);
  for (std::vector<double>& c : g.emphasis) c.assign(F, 0.0);
  // Beats on stressed syllables: a lift, then the stroke landing on the syllable; nods with
  // them, the jaw with every syllable.
  for (const SynthSyllable& syl : plan.syllables) {
    add_bump(g.jaw, fps, syl.time + 0.06, 0.2, syl.stressed ? 1.0 : 0.6);
    if (!syl.stressed) continue;
    // On a keyword the emphasis gesture below replaces the beat (and the nod stays).
    const bool on_keyword = plan.word_gesture[static_cast<std::size_t>(syl.word)] != SynthGesture::None;
    add_bump(g.nod, fps, syl.time + 0.04, 0.4, rng.uniform(0.5, 1.0));
    if (on_keyword) continue;
    const double a = rng.uniform(0.75, 1.15);
    const double w = style.beat_width * rng.uniform(0.9, 1.1);
    add_bump(g.beat_lift, fps, syl.time - 0.65 * w, 0.9 * w, 0.7 * a);
    add_bump(g.beat, fps, syl.time - 0.01, w, a);
    add_bump(g.beat_other, fps, syl.time, w * 1.1, a * rng.uniform(0.6, 1.0));
  }
  // Emphasis gestures on keywords: preparation from 0.35 s before the keyword, stroke (apex)
  // just after its start, a slower retraction.
  for (std::size_t k = 0; k < plan.keyword_times.size(); ++k) {
    const double kt = plan.keyword_times[k];
    const SynthGesture kind = plan.keyword_gestures[k];
    const double apex = kt + rng.uniform(0.15, 0.25);
    const double amplitude = rng.uniform(0.85, 1.1);
    const double end = apex + rng.uniform(0.6, 0.85);
    // A sweep gathers the hands first, then sweeps them out; a point reaches furthest.
    const bool sweep = kind == SynthGesture::Sweep;
    const double prepare = sweep ? 0.15 : (kind == SynthGesture::Point ? 0.45 : 0.35);
    add_bump2(g.emphasis[static_cast<int>(kind)], fps, kt - prepare, apex, end, amplitude);
    if (sweep) add_bump(g.sweep_in, fps, kt - 0.3, 0.5, amplitude);
  }
  // Soft cap, so overlapping gestures do not add up without bound (smooth: tanh).
  const double unit = std::tanh(1.0);
  for (std::vector<double>* c : {&g.beat, &g.beat_lift, &g.beat_other, &g.nod, &g.sweep_in})
    for (double& v : *c) v = std::tanh(v) / unit;
  for (std::vector<double>& c : g.emphasis)
    for (double& v : c) v = std::tanh(v) / unit;
  for (double& v : g.jaw) v = std::tanh(v);
  return g;
}

// Slow idle curves, drawn in this order (members are initialised in declaration order).
struct IdleCurves {
  SmoothNoise sway_x, sway_z, hip_yaw, knees;
  SmoothNoise spine_yaw, spine_roll, head_yaw, head_pitch, head_roll;
  double breath_hz, breath_phase;
  SmoothNoise arm_flex[2], arm_twist[2], arm_elbow[2], curl[2];  // per side

  explicit IdleCurves(Rng& rng)
      : sway_x(rng, 0.05, 0.15),
        sway_z(rng, 0.05, 0.15),
        hip_yaw(rng, 0.03, 0.1),
        knees(rng, 0.05, 0.2),
        spine_yaw(rng, 0.05, 0.2),
        spine_roll(rng, 0.05, 0.2),
        head_yaw(rng, 0.05, 0.15),
        head_pitch(rng, 0.05, 0.2),
        head_roll(rng, 0.05, 0.15),
        breath_hz(rng.uniform(0.2, 0.3)),
        breath_phase(rng.uniform(0.0, 2.0 * kPi)),
        arm_flex{SmoothNoise(rng, 0.2, 0.7), SmoothNoise(rng, 0.2, 0.7)},
        arm_twist{SmoothNoise(rng, 0.2, 0.7), SmoothNoise(rng, 0.2, 0.7)},
        arm_elbow{SmoothNoise(rng, 0.2, 0.8), SmoothNoise(rng, 0.2, 0.8)},
        curl{SmoothNoise(rng, 0.05, 0.3), SmoothNoise(rng, 0.05, 0.3)} {}
};

// Joint indices of the upper body (-1 for a joint the skeleton lacks); [0] left, [1] right.
struct Joints {
  int spine, spine1, spine2, neck, head, jaw;
  int shoulder[2], arm[2], fore[2], hand[2];
  std::vector<std::pair<int, int>> fingers[2];  // (joint, finger index 0..4)

  explicit Joints(const Skeleton& sk)
      : spine(sk.find("Spine")),
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
  const std::vector<double>& weight;
  const IdleCurves& idle;
  const Joints& joints;
  const LowerBody& legs;
};

// Sets joint's rotation at frame f (joints the skeleton lacks are skipped).
void set_rotation(Motion& m, int f, int joint, const glm::dquat& q) {
  if (joint >= 0) m.rotations[m.index(f, joint)] = glm::normalize(q);
}

// How much of any emphasis gesture is under way at frame f, soft-capped like the curves (a
// maximum over the kinds would have corners where two gestures overlap).
double emphasis(const PoseInputs& in, std::size_t f) {
  double e = 0;
  for (const std::vector<double>& c : in.gestures.emphasis) e += c[f];
  return std::tanh(e) / std::tanh(1.0);
}

// Hips and legs (synth_stance.cpp), spine, neck, head and jaw at frame f.
void pose_trunk(Motion& m, int f, double t, const PoseInputs& in) {
  const auto fi = static_cast<std::size_t>(f);
  const Joints& J = in.joints;
  const IdleCurves& idle = in.idle;
  const double S = in.speak[fi], E = emphasis(in, fi);
  const double breath = std::sin(2.0 * kPi * idle.breath_hz * t + idle.breath_phase);

  // The hips over the loaded leg, a little forward while speaking.
  StancePose stance;
  stance.weight = in.weight[fi];
  stance.shift_x = 2.8 * in.weight[fi] + 0.5 * idle.sway_x(t);
  stance.shift_z = 0.8 * idle.sway_z(t) + 0.6 * S;
  stance.yaw_deg = 2.0 * idle.hip_yaw(t);
  stance.bend_noise = 1.0 * idle.knees(t);
  const double pelvis_roll = pose_lower_body(m, f, in.legs, stance);
  // The spine rights the torso over the tilted pelvis and tilts the shoulders a little the other
  // way; it breathes, turns back from the hips' turn and with the dominant hand's beats, and
  // leans in while speaking and on emphasis.
  const double yaw = 3.0 * idle.spine_yaw(t) - 1.5 * idle.hip_yaw(t) - 2.5 * in.gestures.beat[fi] * in.style.gain * S;
  const double roll = 1.5 * idle.spine_roll(t) - 1.25 * pelvis_roll;
  const double pitch = 0.8 * breath + 2.5 * S + 3.0 * E;
  set_rotation(m, f, J.spine, ry(yaw * 0.3) * rx(pitch * 0.3) * rz(roll * 0.5));
  set_rotation(m, f, J.spine1, ry(yaw * 0.35) * rx(pitch * 0.35) * rz(roll * 0.3));
  set_rotation(m, f, J.spine2, ry(yaw * 0.35) * rx(pitch * 0.35 - 1.0 * E) * rz(roll * 0.2));
  // Neck and head: slow look-around, nods on stresses, a lift on emphasis.
  const double h_pitch = 3.0 * idle.head_pitch(t) + 5.0 * in.gestures.nod[fi] * S - 4.0 * E - 0.5 * pitch;
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
  const GestureCurves& g = in.gestures;
  const double S = in.speak[fi];
  const double s = side == 0 ? 1.0 : -1.0;  // mirror: rotations about Y and Z flip sign
  const bool dominant = side == 1;          // the right hand leads the beats and points
  ArmPose p = mix(st.rest, st.talk, S);
  if (!dominant) {
    p.flexion -= 5.0 * S;  // the other hand sits a little lower
    p.elbow -= 8.0 * S;
  }
  // The hands drift while speaking (more than at rest), so they are never still between beats.
  p.flexion += (1.0 + 5.0 * S) * idle.arm_flex[side](t);
  p.twist += (1.0 + 8.0 * S) * idle.arm_twist[side](t);
  p.elbow += (1.5 + 10.0 * S) * idle.arm_elbow[side](t);
  const double k = st.gain * S;
  const double beat = dominant ? g.beat[fi] : st.other_hand * g.beat_other[fi];
  add(p, kBeat, k * beat);
  add(p, kBeatLift, k * (dominant ? 1.0 : st.other_hand) * g.beat_lift[fi]);
  add(p, kOpen, k * g.emphasis[static_cast<int>(SynthGesture::Open)][fi]);
  add(p, kPoint, k * (dominant ? 1.0 : 0.15) * g.emphasis[static_cast<int>(SynthGesture::Point)][fi]);
  add(p, kSweepIn, k * g.sweep_in[fi]);
  add(p, kSweep, k * g.emphasis[static_cast<int>(SynthGesture::Sweep)][fi]);
  add(p, kLift, k * g.emphasis[static_cast<int>(SynthGesture::Lift)][fi]);
  const double E = emphasis(in, fi);
  set_rotation(m, f, J.shoulder[side], rz(s * (5.0 * k * E + 1.5 * k * beat)));
  // Upper arm: from the T-pose down to hanging, turned about its length, then raised out to the
  // side and forward.
  set_rotation(m, f, J.arm[side], rx(-p.flexion) * rz(s * p.abduction) * rz(-s * 90.0) * rx(p.twist));
  set_rotation(m, f, J.fore[side], ry(-s * p.elbow));
  set_rotation(m, f, J.hand[side], rz(-s * p.wrist) * ry(-s * 4.0 * idle.curl[side](t)));
  // Fingers: a relaxed curl that varies slowly and opens on emphasis (the pointing finger most).
  const double point = dominant ? g.emphasis[static_cast<int>(SynthGesture::Point)][fi] * S : 0.0;
  const double c = 18.0 + 8.0 * idle.curl[side](t) - 12.0 * E * S;
  for (const auto& [j, finger] : J.fingers[side]) {
    if (finger == 4)
      set_rotation(m, f, j, ry(s * 0.5 * c) * rz(-s * 0.3 * c));
    else
      set_rotation(m, f, j, rz(-s * c * (1.0 + 0.1 * finger) * (finger == 0 ? 1.0 - point : 1.0 + 0.8 * point)));
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
  const std::vector<double> weight = weight_curve(fps, F, rng);
  const Joints joints(sk);
  const LowerBody legs = lower_body(sk);
  const PoseInputs in{style, gestures, speak, weight, idle, joints, legs};
  for (int f = 0; f < frame_count; ++f) {
    const double t = f / fps;
    pose_trunk(m, f, t, in);
    for (int side = 0; side < 2; ++side) pose_arm(m, f, t, side, in);
  }
  return m;
}

}  // namespace gmg::synth_internal
