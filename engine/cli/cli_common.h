// Internal to the command-line tool: the helpers its subcommands share and the function that
// registers each subcommand (engine/cli/cli_<name>.cpp). Each add_<name>_command adds the
// subcommand with its options to app and sets its callback; the options' storage lives as long
// as the callback (and so as app). A callback reports a problem by throwing gmg::Error; cli_main
// prints it and exits with 1, or with 2 for a UsageError.
//
// Conventions of every subcommand: exit 0 on success; 2 when the command line is wrong, found
// from its text alone before any file is read (CLI11's parse errors, an unknown command or option,
// with the nearest name, a value out of range or of the wrong form, options that contradict or
// need each other, an output whose extension names no format the option writes: UsageError); 1
// when an input file cannot be read or holds what gmg refuses, an output cannot be written where
// it is asked for, or the work fails (Error). `gmg batch` keeps its own: 1 some clip failed, 2 the
// batch could not start. Each error is one line "gmg: error: ..." with its non-printable bytes
// escaped; an interrupt ends the process by its signal (engine/core/interrupt.h);
// `--help` shows every option's default; JSON output has snake_case keys and numbers in their
// shortest round-trip form.
#pragma once

#include <cstdint>
#include <functional>
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
class Option;
}  // namespace CLI

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
  // The defaults, then the file, then each --set, then --seed; validated. A problem of the file
  // is an Error naming it (exit 1); a --set that names no key, holds no valid value or breaks a
  // rule is a UsageError (exit 2).
  Config make() const;
};

// The checks shared by the options of every subcommand (so options added later get them too):
// a seed or count is a whole number from 0 to `max` ("-1" is refused, not wrapped to 2^64 - 1,
// and 2^64 not saturated to it), a duration a number above 0, each refused with a short message
// saying what the value given is not, with readable bounds ("--still: '-1' is not a time in
// seconds, 0 or above"); nan and inf are no number.
CLI::Option* whole_number(CLI::Option* option, std::uint64_t max = UINT64_MAX);
CLI::Option* number_check(CLI::Option* option, const std::function<bool(double)>& ok, const std::string& wanted);
CLI::Option* positive_number(CLI::Option* option);
CLI::Option* seconds_number(CLI::Option* option);
CLI::Option* number_from_to(CLI::Option* option, double lo, double hi);
// --transcript-format: auto, tsv, textgrid or json (text::parse_transcript_format's message).
CLI::Option* transcript_format_check(CLI::Option* option);

// The most --jobs a command takes: far above any machine's cores, far below what would make
// thousands of threads.
inline constexpr std::uint64_t kMaxJobs = 1024;

// check_output_file (engine/core/files.h) for each output that is given: its kind, extension
// and folder, before any work. A wrong extension is a UsageError (check_output_extensions), the
// rest, which depends on the file system, an Error.
struct OutputSpec {
  std::string option;  // "-o"
  std::string path;    // "" = not given
  std::vector<std::string> extensions;
};
void check_outputs(const std::vector<OutputSpec>& outputs);
// Only the extensions, from the command line's text: each subcommand calls it first, before it
// reads any file. `hint` is added to the message.
void check_output_extensions(const std::vector<OutputSpec>& outputs, const std::string& hint = "");

// The extensions of each kind of output, spelled once.
extern const std::vector<std::string> kJsonExtensions;   // .json
extern const std::vector<std::string> kGraphExtensions;  // .gmg
extern const std::vector<std::string> kCsvExtensions;    // .csv

// "gmg: warning: <w>" on standard error for each, escaped (escape_nonprintable).
void print_warnings(const std::vector<std::string>& warnings);

// --allow-silence: take audio that cannot be speech as it is (SpeechFiles::allow_silence).
void add_allow_silence_flag(CLI::App* cmd, bool& allow);

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
// one line "gmg: error: ..."). Interrupted by SIGINT, SIGTERM or SIGHUP, the first signal lets
// clips under way finish and writes the summary, then the process ends by the signal
// (Interrupted, engine/core/interrupt.h); a second one ends it at once.
void add_batch_command(CLI::App& app, int* exit_code);

}  // namespace gmg
