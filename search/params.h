// Search parameters (paper 4.2, A.1, section 5; SPEC "Beam search", "Feature-based
// initialisation", "Fallbacks").
//
// Owned by the search stage: search_params_validate checks them once, before planning.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/enum_names.h"

namespace gmg {

// How start nodes are chosen (paper 4.2.3; "random" is Table 2's weak initialisation).
enum class InitMode : std::uint8_t { Feature, Random };
inline constexpr EnumName<InitMode> kInitModeNames[] = {{InitMode::Feature, "feature"}, {InitMode::Random, "random"}};

struct SearchParams {
  int l_npaths = 20;        // beam width and number of start nodes
  double lambda_w = 1.0;    // weight of the summed edge weights in the path cost
  double lambda_len = 1.0;  // weight of the length mismatch |1 - len/l_sub|
  int l_feat = 10;          // key-node feature length
  double lambda_full = 1.0;
  double lambda_first = 1.0;
  double lambda_occ = 0.5;
  std::vector<double> w_full = {1, .5, .5, .2, .2, .2, .1, .1, .1, .1};
  // Retries with fresh start nodes before a fallback. 3 gives the next 60 key nodes a chance
  // (with l_npaths 20) while keeping a hopeless subsequence cheap.
  int retries = 3;
  // The beam stops after max_length_factor * l_sub + 2 extensions: no path longer than
  // 1.1 * l_sub can be accepted, so 1.5 leaves room for paths that wander and come back.
  double max_length_factor = 1.5;
  bool fallbacks = true;              // false: report failures instead (paper's Table 2 ablation)
  InitMode init = InitMode::Feature;  // feature (paper 4.2.3) or random (weak initialisation)
  // Fallback 2 drops this growing share of stopping nodes per round: 0.25, 0.5, 0.75, 1.0.
  int ignore_rounds = 4;
};

// Throws gmg::Error naming the first key out of range.
void search_params_validate(const SearchParams& params);

}  // namespace gmg
