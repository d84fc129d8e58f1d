#include "engine/assemble/params.h"

#include "engine/core/error.h"

namespace gmg {

void blend_params_validate(const BlendParams& p) { require_param(p.l_blend >= 0, "l_blend must be >= 0"); }

}  // namespace gmg
