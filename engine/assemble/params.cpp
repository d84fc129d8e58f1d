#include "engine/assemble/params.h"

#include "engine/core/error.h"

namespace gmg {

void blend_params_validate(const BlendParams& p) {
  require_param(p.l_blend >= 0 && p.l_blend <= 1000, "l_blend must be in [0, 1000]");
  require_param(p.halflife_s > 0.0 && p.halflife_s <= 10.0, "transition_halflife must be in (0, 10] seconds");
  require_param(p.root_halflife_s > 0.0 && p.root_halflife_s <= 3600.0, "root_halflife must be in (0, 3600] seconds");
  require_param(p.foot_step_s > 0.0 && p.foot_step_s <= 10.0, "foot_step_s must be in (0, 10] seconds");
  require_param(p.spine_follow >= 0.0 && p.spine_follow <= 1.0, "spine_follow must be in [0, 1]");
  require_param(p.beat_shift >= 0 && p.beat_shift <= 30, "beat_shift must be in [0, 30] frames");
  require_param(p.beat_rate >= 1.0 && p.beat_rate <= 2.0, "beat_rate must be in [1, 2]");
}

}  // namespace gmg
