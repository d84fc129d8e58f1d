// Assembly parameters: how path pieces are joined (paper 4.2.4; SPEC "Blending").
#pragma once

#include <cstdint>

#include "engine/core/enum_names.h"

namespace gmg {

// Shape of the blend weights over a junction window.
enum class BlendCurve : std::uint8_t { Linear, Sigmoid };
inline constexpr EnumName<BlendCurve> kBlendCurveNames[] = {{BlendCurve::Linear, "linear"},
                                                            {BlendCurve::Sigmoid, "sigmoid"}};

// How a junction is blended (see BlendParams::mode).
enum class BlendMode : std::uint8_t { Offset, Crossfade };
inline constexpr EnumName<BlendMode> kBlendModeNames[] = {{BlendMode::Offset, "offset"},
                                                          {BlendMode::Crossfade, "crossfade"}};

struct BlendParams {
  // Frames on each side of a junction. Retries restart the search at other key nodes, so some
  // junctions join distant poses: on BEAT2 (2_scott_0_2_2 from 0_1_1) 8 frames (0.27 s at
  // 30 fps) halves the output's mean jerk against 4 (94.8k -> 50.1k cm/s^3), while 12 also
  // lowers Div, i.e. starts to smear strokes.
  int l_blend = 8;
  BlendCurve curve = BlendCurve::Sigmoid;
  // Offset: keep both pieces' own motion and spread the junction's excess jump (the right
  // piece's first frame minus where the left piece was heading) over the window, so a junction
  // that is already continuous is left as it is. Crossfade: SPEC's literal cross-fade of
  // "left, then its last frame held" into "right's first frame held, then right"; its holds
  // stall one side while the other moves, so even a continuous junction speeds up and slows
  // down (a step of v (1 - w) + dw * l_blend * v > v). Offset is the default for that reason.
  BlendMode mode = BlendMode::Offset;
};

// Throws gmg::Error naming the first key out of range.
void blend_params_validate(const BlendParams& params);

}  // namespace gmg
