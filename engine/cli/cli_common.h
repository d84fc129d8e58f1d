// Internal to the command-line tool: the helpers its subcommands share and the function that
// registers each subcommand (engine/cli/cli_<name>.cpp). Each add_<name>_command adds the
// subcommand with its options to app and sets its callback; the options' storage lives as long
// as the callback (and so as app). A callback reports a problem by throwing gmg::Error; cli_main
// prints it and exits with 1, or with 2 for a UsageError.
//
// Conventions of every subcommand: exit 0 on success, 1 on an input or processing error, 2 on a
// usage error (CLI11's parse errors and UsageError), each error one line "gmg: error: ...";
// `--help` shows every option's default; JSON output has snake_case keys and numbers in their
// shortest round-trip form.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/config/config.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/json.h"  // write_json_file

namespace CLI {
class App;
}

namespace gmg {

// A command line that cannot mean anything (options that contradict or need each other): exits
// 2 like CLI11's own parse errors, not 1 like an input that fails.
class UsageError : public Error {
 public:
  using Error::Error;
};

// --config FILE and --set key=value (and optionally --seed), shared by the subcommands that take
// parameters.
struct ConfigOptions {
  std::string file;
  std::vector<std::string> sets;
  std::optional<std::uint64_t> seed;

  void add(CLI::App* cmd, bool with_seed);
  // The defaults, then the file, then each --set, then --seed; validated.
  Config make() const;
};

// The files a config reads, for check_outputs_apart: the --config file and the keyword lexicon
// (keywords=FILE).
std::vector<NamedFile> config_input_files(const ConfigOptions& options, const Config& config);

// "none" means the clip has no transcript (so a transcript can be left out inside a list).
std::string transcript_or_none(const std::string& t);

void add_build_command(CLI::App& app);
void add_inspect_command(CLI::App& app);
void add_reenact_command(CLI::App& app);
void add_evaluate_command(CLI::App& app);
void add_ablation_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_config_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_analyse_command(CLI::App& app);
void add_convert_command(CLI::App& app);
// Registers the "batch" subcommand on app (with its own --config FILE and --set key=value options,
// applied in that order, then --seed). Its callback runs batch_run with progress on std::cerr and
// sets *exit_code: 0 every clip made or skipped, 1 some clip failed, 2 a setup error (printed as
// one line "gmg: error: ..."), 130 interrupted by SIGINT/SIGTERM (the first signal lets clips
// under way finish and writes the summary; a second one kills).
void add_batch_command(CLI::App& app, int* exit_code);

}  // namespace gmg
