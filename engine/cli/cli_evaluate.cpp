// `gmg evaluate`: objective metrics of a generated motion.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/cli/cli_common.h"
#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/evaluate/evaluate_files.h"
#include "engine/evaluate/plot.h"

namespace gmg {
namespace {

struct EvaluateArgs {
  EvaluateInputs inputs;
  EvaluateOptions options;
  std::string bins = "overflow";
  bool json = false;
  std::string output;
};

void run_evaluate(EvaluateArgs& a) {
  a.options.metrics.hist_bins = *enum_from_name(kHistogramBinsNames, a.bins);
  const EvaluateInputs& in = a.inputs;
  std::vector<NamedFile> inputs = {{"--generated", in.generated}, {"--truth", in.truth},
                                   {"--audio", in.audio},         {"--report", in.report},
                                   {"--reference", in.reference}, {"--transcript", in.transcript}};
  for (const std::string& o : in.other_audio) inputs.push_back({"--other-audio", o});
  if (!in.other_audio.empty() && in.audio.empty()) throw UsageError("--other-audio needs --audio");
  check_output_extensions({{"-o", a.output, kJsonExtensions}, {"--plot", in.plot, kPlotExtensions}});
  check_outputs_apart({{"-o", a.output}, {"--plot", in.plot}}, inputs);
  check_outputs({{"-o", a.output, kJsonExtensions}, {"--plot", in.plot, kPlotExtensions}});
  OutputTransaction outputs;  // the plot and the JSON, both or neither
  const EvaluateResult r = evaluate_files(in, a.options);
  if (!a.output.empty()) write_json_file(a.output, r.json);
  outputs.commit();
  print_warnings(r.warnings);
  std::cout << json_dump(r.json, a.json ? -1 : 2) << "\n";
}

}  // namespace

void add_evaluate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("evaluate", "objective metrics of a generated motion");
  auto a = std::make_shared<EvaluateArgs>();
  EvaluateInputs& in = a->inputs;
  cmd->add_option("--generated", in.generated, "generated motion, BVH or SMPL-X .npz")->required();
  cmd->add_option("--truth", in.truth, "ground-truth motion, BVH or .npz (same skeleton and length)");
  cmd->add_option("--skeleton", in.skeleton, "BVH whose hierarchy gives .npz motions their skeleton");
  cmd->add_option("--audio", in.audio, "the speech (beat consistency and speech correlation, with a control)");
  cmd->add_option("--other-audio", in.other_audio,
                  "other speech (repeatable): every sync metric is also scored against it, as GENEA pairs motion with "
                  "mismatched speech; lift = own speech minus the mean over these");
  cmd->add_option("--transcript", in.transcript,
                  "the speech's TextGrid with a phones tier (the face's viseme contrast)");
  cmd->add_option("--report", in.report, "the reenactment report (failures, fallbacks, transitions, junctions)");
  cmd->add_option("--reference", in.reference,
                  "the reference capture, BVH or graph (.gmg): jump threshold, and ratios when there is no truth");
  cmd->add_flag("--trim", in.trim, "cut the longer of generated and truth to the shorter (with a warning)");
  cmd->add_option("--hellinger", a->bins, "speed histogram bins: overflow (ours) or genea")
      ->check(CLI::IsMember({"overflow", "genea"}))
      ->capture_default_str();
  positive_number(cmd->add_option("--hist-width", a->options.metrics.hist_bin_width, "histogram bin width, cm/s"))
      ->capture_default_str();
  cmd->add_option("--plot", in.plot, "draw speeds, onset strength, onsets and junctions over time (.png or .svg)");
  cmd->add_flag("--json", a->json, "print one JSON object on standard output");
  cmd->add_option("-o,--output", a->output, "also write the JSON to this file (.json)");
  add_allow_silence_flag(cmd, in.allow_silence);
  cmd->callback([a] { run_evaluate(*a); });
}

}  // namespace gmg
