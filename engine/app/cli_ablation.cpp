// `gmg ablation`: the paper's Table 2 on one recording split in time.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/app/ablation.h"
#include "engine/app/cli_common.h"
#include "engine/core/files.h"

namespace gmg {
namespace {

struct AblationArgs {
  std::string motion, audio, transcript, csv;
  double share = 2.0 / 3.0;
  int seeds = 5;
  ConfigOptions config;
};

void run_ablation(const AblationArgs& a) {
  std::vector<std::uint64_t> seeds;
  for (int i = 0; i < a.seeds; ++i) seeds.push_back(static_cast<std::uint64_t>(i + 1));
  const auto rows = ablation_run(a.motion, a.audio, transcript_or_none(a.transcript), a.share, seeds, a.config.make());
  std::cout << ablation_markdown(rows);
  if (!a.csv.empty()) {
    const std::string csv = ablation_csv(rows);
    write_file_atomically(a.csv, [&](std::ostream& os) { os << csv; });
  }
}

}  // namespace

void add_ablation_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("ablation", "the paper's Table 2: split one recording in time, score five setups");
  auto a = std::make_shared<AblationArgs>();
  cmd->add_option("--motion", a->motion, "recording's BVH")->required();
  cmd->add_option("--audio", a->audio, "its WAV")->required();
  cmd->add_option("--transcript", a->transcript, "its transcript (optional)");
  cmd->add_option("--reference-share", a->share, "share of the recording used as reference (default 2/3)");
  cmd->add_option("--seeds", a->seeds, "seeds per setup (1..)")->check(CLI::PositiveNumber);
  cmd->add_option("--csv", a->csv, "also write the table as CSV");
  a->config.add(cmd, false);
  cmd->callback([a] { run_ablation(*a); });
}

}  // namespace gmg
