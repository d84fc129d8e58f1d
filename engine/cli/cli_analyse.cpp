// `gmg analyse`: the speech analysis a reenactment is planned from, as JSON or CSV.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/cli/cli_common.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/core/strings.h"
#include "engine/pipeline/speech_report.h"

namespace gmg {
namespace {

struct AnalyseArgs {
  std::string audio, transcript, tier, output;
  double fps = 30.0;
  ConfigOptions config;
};

void run_analyse(const AnalyseArgs& a) {
  const bool csv = ends_with_ci(a.output, ".csv");
  check_output_extensions({{"-o", a.output, {".json", ".csv"}}});
  const Config cfg = a.config.make();
  std::vector<NamedFile> inputs = {{"--audio", a.audio}, {"--transcript", transcript_or_none(a.transcript)}};
  for (const NamedFile& f : config_input_files(a.config, cfg)) inputs.push_back(f);
  check_outputs_apart({{"-o", a.output}}, inputs);
  const nlohmann::ordered_json report =
      speech_report_json({a.audio, transcript_or_none(a.transcript), text::TranscriptFormat::Auto, a.tier}, a.fps, cfg);
  if (a.output.empty()) {
    std::cout << json_dump(report, 2) << "\n";
  } else if (csv) {
    const std::string text = speech_report_csv(report);
    write_file_atomically(a.output, [&](std::ostream& os) { os << text; });
  } else {
    write_json_file(a.output, report);
  }
}

}  // namespace

void add_analyse_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "analyse", "the speech analysis reenactment plans from: onsets, keywords, per-frame loudness and pauses");
  auto a = std::make_shared<AnalyseArgs>();
  cmd->add_option("--audio", a->audio, "the speech (WAV, FLAC, MP3, ...)")->required();
  cmd->add_option("--transcript", a->transcript, "its transcript (TSV, TextGrid, Google/Whisper JSON; optional)");
  cmd->add_option("--tier", a->tier, "TextGrid tier of the words");
  number_check(
      cmd->add_option("--fps", a->fps, "frame rate of the motion grid"), [](double x) { return x > 0 && x <= 1000; },
      "a frame rate above 0 and at most 1000")
      ->capture_default_str();
  cmd->add_option("-o,--output", a->output,
                  "write JSON (.json: everything) or CSV (.csv: one line per onset and keyword); default: JSON on "
                  "standard output");
  a->config.add(cmd, false);
  cmd->callback([a] { run_analyse(*a); });
}

}  // namespace gmg
