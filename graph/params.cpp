#include "graph/params.h"

#include "engine/core/error.h"

namespace gmg {

void graph_params_validate(const GraphParams& p) {
  require_param(p.lambda_pos >= 0 && p.lambda_vel >= 0 && p.lambda_pos + p.lambda_vel > 0,
                "lambda_pos and lambda_vel must be >= 0 and not both 0");
  require_param(p.l_cn >= 1, "l_cn must be >= 1");
  require_param(p.l_pn >= 1, "l_pn must be >= 1");
  require_param(p.min_onset_strength >= 0, "min_onset_strength must be >= 0");
  require_param(p.break_jump_factor > 1, "break_jump_factor must be > 1");
  require_param(p.max_transitions >= 0, "max_transitions must be >= 0 (0: no bound)");
  require_param(p.candidates_per_transition >= 1, "candidates_per_transition must be >= 1");
  require_param(p.exact_frames >= 0, "exact_frames must be >= 0");
  require_param(p.ann_checks >= 0, "ann_checks must be >= 0 (0: exhaustive)");
}

}  // namespace gmg
