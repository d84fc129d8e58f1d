// `gmg evaluate`: objective metrics of a generated motion.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/app/cli_common.h"
#include "engine/metrics/evaluate.h"

namespace gmg {
namespace {

struct EvaluateArgs {
  EvaluateInputs inputs;
  bool json = false;
  std::string output;
};

void run_evaluate(const EvaluateArgs& a) {
  const nlohmann::ordered_json j = evaluate_files(a.inputs, MetricParams{});
  if (!a.output.empty()) write_json_file(a.output, j);
  std::cout << (a.json ? j.dump() : j.dump(2)) << "\n";
}

}  // namespace

void add_evaluate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("evaluate", "objective metrics of a generated motion");
  auto a = std::make_shared<EvaluateArgs>();
  cmd->add_option("--generated", a->inputs.generated, "generated BVH")->required();
  cmd->add_option("--truth", a->inputs.truth, "ground-truth BVH (same skeleton and length)");
  cmd->add_option("--audio", a->inputs.audio, "the speech WAV (for beat consistency)");
  cmd->add_option("--report", a->inputs.report, "the reenactment report (for failures and fallbacks)");
  cmd->add_flag("--json", a->json, "print one JSON object on standard output");
  cmd->add_option("-o,--output", a->output, "also write the JSON to this file");
  cmd->callback([a] { run_evaluate(*a); });
}

}  // namespace gmg
