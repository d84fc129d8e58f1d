// The paper's Table 2 ablation: a reference clip split in time (reference = first part, test =
// the rest with its audio and words), reenacted under the full setup and four weakened ones
// over several seeds, scored against the held-out true motion.
#pragma once

#include <string>
#include <vector>

#include "engine/app/config.h"

namespace gmg {

struct AblationRow {
  std::string setup;
  std::vector<double> syn, bc, div;  // one per seed
  std::vector<int> failures;         // one per seed
};

// motion/audio/transcript: one recording ("" transcript = none); reference_share of its
// duration (e.g. 2/3) becomes the reference, the rest the test.
std::vector<AblationRow> ablation_run(const std::string& motion, const std::string& audio, const std::string& transcript,
                                      double reference_share, const std::vector<std::uint64_t>& seeds, const Config& base);

// Mean ± standard deviation per metric, as a Markdown table and as CSV.
std::string ablation_markdown(const std::vector<AblationRow>& rows);
std::string ablation_csv(const std::vector<AblationRow>& rows);

}  // namespace gmg
