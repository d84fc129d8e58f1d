// `gmg ablation`: the paper's Table 2 with baselines, on time folds of one recording.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/ablation/ablation.h"
#include "engine/cli/cli_common.h"
#include "engine/core/files.h"

namespace gmg {
namespace {

struct AblationArgs {
  std::string motion, audio, transcript, skeleton, csv, bins = "overflow";
  AblationOptions options;
  int seeds = 5;
  ConfigOptions config;
};

void run_ablation(AblationArgs& a) {
  check_output_extensions({{"--csv", a.csv, kCsvExtensions}});
  a.options.seeds.clear();
  for (int i = 0; i < a.seeds; ++i) a.options.seeds.push_back(static_cast<std::uint64_t>(i + 1));
  a.options.metrics.hist_bins = *enum_from_name(kHistogramBinsNames, a.bins);
  const Config cfg = a.config.make();
  std::vector<NamedFile> inputs = {{"--motion", a.motion},
                                   {"--audio", a.audio},
                                   {"--transcript", transcript_or_none(a.transcript)},
                                   {"--skeleton", a.skeleton}};
  for (const NamedFile& f : config_input_files(a.config, cfg)) inputs.push_back(f);
  check_outputs_apart({{"--csv", a.csv}}, inputs);
  check_outputs({{"--csv", a.csv, kCsvExtensions}});
  const AblationResult result =
      ablation_run({a.motion, a.audio, transcript_or_none(a.transcript), a.skeleton}, a.options, cfg);
  std::cout << ablation_markdown(result);
  if (!a.csv.empty()) {
    const std::string csv = ablation_csv(result);
    write_file_atomically(a.csv, [&](std::ostream& os) { os << csv; });
  }
}

}  // namespace

void add_ablation_command(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("ablation", "the paper's Table 2 with baselines: time folds of one recording, seven setups");
  auto a = std::make_shared<AblationArgs>();
  cmd->add_option("--motion", a->motion, "the recording's motion: BVH, or SMPL-X .npz with --skeleton")->required();
  cmd->add_option("--audio", a->audio, "its WAV")->required();
  cmd->add_option("--transcript", a->transcript, "its transcript (optional)");
  cmd->add_option("--skeleton", a->skeleton, "BVH whose hierarchy gives an .npz --motion its skeleton");
  number_check(
      cmd->add_option("--folds", a->options.folds, "time folds: each K-th is the test part once (>= 2)"),
      [](double x) { return x >= 2 && x <= 1000 && x == static_cast<int>(x); }, "a whole number from 2 to 1000")
      ->capture_default_str();
  positive_number(whole_number(cmd->add_option("--seeds", a->seeds, "seeds per setup and fold (1..)"), 10000))
      ->capture_default_str();
  cmd->add_option("--hellinger", a->bins, "speed histogram bins: overflow (ours) or genea")
      ->check(CLI::IsMember({"overflow", "genea"}))
      ->capture_default_str();
  positive_number(cmd->add_option("--hist-width", a->options.metrics.hist_bin_width, "histogram bin width, cm/s"))
      ->capture_default_str();
  cmd->add_option("--csv", a->csv, "also write the table as CSV (.csv)");
  a->config.add(cmd, false);
  cmd->callback([a] { run_ablation(*a); });
}

}  // namespace gmg
