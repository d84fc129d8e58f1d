// Assembly parameters: how path pieces are joined (paper 4.2.4; SPEC "Blending").
#pragma once

#include <cstdint>

#include "engine/core/enum_names.h"

namespace gmg {

// Shape of the blend weights over a junction window.
enum class BlendCurve : std::uint8_t { Linear, Sigmoid };
inline constexpr EnumName<BlendCurve> kBlendCurveNames[] = {{BlendCurve::Linear, "linear"},
                                                            {BlendCurve::Sigmoid, "sigmoid"}};

// How pieces are joined (see BlendParams::mode).
enum class BlendMode : std::uint8_t { Inertialize, Offset, Crossfade };
inline constexpr EnumName<BlendMode> kBlendModeNames[] = {
    {BlendMode::Inertialize, "inertialize"}, {BlendMode::Offset, "offset"}, {BlendMode::Crossfade, "crossfade"}};

// What the root joint's horizontal position does at a transition (engine/assemble/transitions.h).
enum class RootMode : std::uint8_t { Anchor, Free };
inline constexpr EnumName<RootMode> kRootModeNames[] = {{RootMode::Anchor, "anchor"}, {RootMode::Free, "free"}};

struct BlendParams {
  // Inertialize (the default, engine/assemble/transitions.h): the output is read at continuous
  // source time and every transition, a junction that did not continue or an unnatural edge
  // inside a path, carries its pose and velocity offset over and lets it decay (half-life
  // halflife_s). Offset and Crossfade join separately resampled pieces over l_blend frames each
  // side (engine/assemble/blend.h); they play unnatural edges inside a path unblended.
  BlendMode mode = BlendMode::Inertialize;
  // Inertialization half-life. 0.3 s carries an arm through a junction at its own speed and hands
  // over within about 1.4 s: the speech-driven planner jumps often and to far poses, and a shorter
  // half-life left visibly faster steps (docs/decisions.md, Parameters).
  double halflife_s = 0.3;
  // Anchor: a new piece's root continues horizontally from where the output was and relaxes
  // toward the capture's own position with half-life root_halflife_s. Free: the root plays its
  // capture position (and blends between capture spots), the landed behaviour.
  RootMode root = RootMode::Anchor;
  // Slow enough that the drift back stays well below the capture's own root speed (an offset of
  // 30 cm relaxing with a 5 s half-life moves at most 4 cm/s; with 2 s the drift shifted the
  // low-speed part of every joint's speed histogram, Hellinger 0.145 against 0.099 at 4 s on
  // BEAT2), fast enough that the speaker does not wander off the reference's standing area over
  // a minute of new speech.
  double root_halflife_s = 5.0;
  // Inertialize only: feet the source has on the ground stay where they are (two-joint IK on
  // the legs, engine/assemble/foot_lock.h) instead of gliding while a transition decays.
  bool foot_lock = true;
  // A released foot steps to where the leg puts it in this time, as a relaxed step takes (0.35 s
  // added 0.09 to BEAT2's jerk ratio, 0.5 s 0.05);
  // decaying the offset like a transition's instead (0.2 s half-life) dragged the foot along the
  // floor, BEAT2 slide share 4 x the capture's.
  double foot_step_s = 0.5;
  // The layered body (engine/assemble/layers.h): how much of the pelvis's difference between the
  // lower and the upper layer the spine takes up. 1: the chest keeps the upper layer's own posture
  // (the captured spine's answer to its own pelvis); 0: it rides rigidly on the lower pelvis.
  double spine_follow = 1.0;
  // Inertialize, natural planner: where the upper body plays on through an onset of the new speech,
  // the reference's nearest kinematic beat within beat_shift frames is moved onto it, the playback
  // speed staying within [1 / beat_rate, beat_rate] of the piece's (engine/assemble/timeline.h
  // BeatAlignment). 0: off.
  int beat_shift = 4;
  double beat_rate = 1.33;

  // Offset and Crossfade only: frames on each side of a junction. Retries restart the search at other key nodes, so
  // some junctions join distant poses: on BEAT2 (2_scott_0_2_2 from 0_1_1) 8 frames (0.27 s at 30 fps) halves the
  // output's mean jerk against 4 (94.8k -> 50.1k cm/s^3), while 12 also lowers Div, i.e. starts to smear strokes.
  int l_blend = 8;
  BlendCurve curve = BlendCurve::Sigmoid;
  // Offset: keep both pieces' own motion and spread the junction's excess jump (the right
  // piece's first frame minus where the left piece was heading) over the window, so a junction
  // that is already continuous is left as it is. Crossfade: SPEC's literal (the paper's)
  // cross-fade of "left, then its last frame held" into "right's first frame held, then right";
  // its holds stall one side while the other moves, so even a continuous junction speeds up and
  // slows down (a step of v (1 - w) + dw * l_blend * v > v).
};

// Throws gmg::Error naming the first key out of range.
void blend_params_validate(const BlendParams& params);

}  // namespace gmg
