#include "engine/assemble/params.h"

#include "engine/core/error.h"

namespace gmg {

void blend_params_validate(const BlendParams& p) {
  require_param(p.l_blend >= 0, "l_blend must be >= 0");
  require_param(p.curve == "linear" || p.curve == "sigmoid", "blend_curve must be 'linear' or 'sigmoid'");
  require_param(p.mode == "offset" || p.mode == "crossfade", "blend_mode must be 'offset' or 'crossfade'");
}

}  // namespace gmg
