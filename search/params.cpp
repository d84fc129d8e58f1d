#include "search/params.h"

#include "engine/core/error.h"

namespace gmg {

void search_params_validate(const SearchParams& p) {
  require_param(p.l_npaths >= 1, "l_npaths must be >= 1");
  require_param(p.lambda_w >= 0 && p.lambda_len >= 0, "lambda_w and lambda_len must be >= 0");
  require_param(p.l_feat >= 1, "l_feat must be >= 1");
  require_param(static_cast<int>(p.w_full.size()) == p.l_feat, "w_full must have l_feat (" + std::to_string(p.l_feat) +
                                                                   ") entries, has " + std::to_string(p.w_full.size()));
  require_param(p.retries >= 0, "retries must be >= 0");
  require_param(p.max_length_factor >= 1.1, "max_length_factor must be >= 1.1");
  require_param(p.ignore_rounds >= 1, "ignore_rounds must be >= 1");
}

}  // namespace gmg
