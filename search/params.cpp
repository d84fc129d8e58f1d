#include "search/params.h"

#include "engine/core/error.h"

namespace gmg {

// The upper bounds keep a typo from asking for gigabytes: the beam holds l_npaths x out-degree
// entries per step and every retry repeats it.
void search_params_validate(const SearchParams& p) {
  require_param(p.l_npaths >= 1 && p.l_npaths <= 1000, "l_npaths must be in [1, 1000]");
  require_param(p.lambda_w >= 0 && p.lambda_len >= 0, "lambda_w and lambda_len must be >= 0");
  require_param(p.l_feat >= 1 && p.l_feat <= 100, "l_feat must be in [1, 100]");
  require_param(static_cast<int>(p.w_full.size()) == p.l_feat, "w_full must have l_feat (" + std::to_string(p.l_feat) +
                                                                   ") entries, has " + std::to_string(p.w_full.size()));
  require_param(p.retries >= 0 && p.retries <= 100, "retries must be in [0, 100]");
  require_param(p.max_length_factor >= 1.1 && p.max_length_factor <= 10.0, "max_length_factor must be in [1.1, 10]");
  require_param(p.ignore_rounds >= 1 && p.ignore_rounds <= 100, "ignore_rounds must be in [1, 100]");
  require_param(p.start_candidates >= 0 && p.start_candidates <= 100000000,
                "start_candidates must be in [0, 100000000]");
  require_param(p.junction_rank >= 0 && p.junction_beam >= 0, "junction_rank and junction_beam must be >= 0");
  require_param(p.continue_min > 0 && p.continue_min <= 1.0 && p.continue_max >= 1.0 && p.continue_max <= 4.0,
                "continue_min must be in (0, 1] and continue_max in [1, 4]");
  require_param(p.merge_below >= 0 && p.merge_below <= 1000, "merge_below must be in [0, 1000]");
  require_param(p.variety >= 0 && p.variety <= 0.9, "variety must be in [0, 0.9]");
  require_param(p.speech_weight >= 0 && p.speech_weight <= 1000, "speech_weight must be in [0, 1000]");
  require_param(p.beat_weight >= 0 && p.beat_weight <= 1000, "beat_weight must be in [0, 1000]");
  require_param(p.rest_weight >= 0 && p.rest_weight <= 1000, "rest_weight must be in [0, 1000]");
  require_param(p.reuse_weight >= 0 && p.reuse_weight <= 1000, "reuse_weight must be in [0, 1000]");
  require_param(p.reuse_halflife_s > 0 && p.reuse_halflife_s <= 1e6, "reuse_halflife_s must be in (0, 1e6]");
  require_param(p.reuse_cap_plays >= 0 && p.reuse_cap_plays <= 100, "reuse_cap_plays must be in [0, 100]");
  require_param(p.reuse_cap_window_s >= 0 && p.reuse_cap_window_s <= 1e6, "reuse_cap_window_s must be in [0, 1e6]");
  require_param(p.no_return_s >= 0 && p.no_return_s <= 1e6, "no_return_s must be in [0, 1e6]");
  require_param(p.rest_min_s > 0 && p.rest_min_s <= 10, "rest_min_s must be in (0, 10]");
  require_param(p.rest_lead_s > 0 && p.rest_lead_s <= 5, "rest_lead_s must be in (0, 5]");
}

}  // namespace gmg
