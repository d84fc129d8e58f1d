#include "engine/cli/cli_common.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <functional>
#include <iostream>
#include <limits>

#include <CLI/CLI.hpp>

#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/core/strings.h"
#include "text/transcript.h"

namespace gmg {

const std::vector<std::string> kJsonExtensions = {".json"};
const std::vector<std::string> kGraphExtensions = {".gmg"};
const std::vector<std::string> kCsvExtensions = {".csv"};

CLI::Option* whole_number(CLI::Option* option, std::uint64_t max) {
  return option->check(CLI::Validator(
      [max](std::string& v) -> std::string {
        const bool digits = !v.empty() && std::all_of(v.begin(), v.end(), [](char c) { return c >= '0' && c <= '9'; });
        if (!digits) return "'" + v + "' is not a whole number 0 or above";
        std::uint64_t x = 0;
        const auto r = std::from_chars(v.data(), v.data() + v.size(), x);
        if (r.ec != std::errc() || x > max) return v + " is out of range (0 to " + std::to_string(max) + ")";
        return "";
      },
      ""));
}

CLI::Option* number_check(CLI::Option* option, const std::function<bool(double)>& ok, const std::string& wanted) {
  return option->check(CLI::Validator(
      [ok, wanted](std::string& v) -> std::string {
        const std::optional<double> x = parse_number(v);  // not nan or inf
        return x && ok(*x) ? std::string() : "'" + shorten_for_message(v) + "' is not " + wanted;
      },
      ""));
}

CLI::Option* positive_number(CLI::Option* option) {
  return number_check(
      option, [](double x) { return x > 0; }, "a number above 0");
}

CLI::Option* seconds_number(CLI::Option* option) {
  return number_check(
      option, [](double x) { return x >= 0; }, "a time in seconds, 0 or above");
}

CLI::Option* number_from_to(CLI::Option* option, double lo, double hi) {
  return number_check(
      option, [lo, hi](double x) { return x >= lo && x <= hi; },
      "a number from " + format_number(lo) + " to " + format_number(hi));
}

CLI::Option* transcript_format_check(CLI::Option* option) {
  return option->check(CLI::Validator(
      [](std::string& v) -> std::string {
        try {
          text::parse_transcript_format(v);
        } catch (const Error& e) {
          return e.what();
        }
        return "";
      },
      ""));
}

void ConfigOptions::add(CLI::App* cmd, bool with_seed) {
  cmd->add_option("--config", file, "JSON file of parameters (see 'gmg config')");
  cmd->add_option("--set", sets, "parameter override key=value (repeatable)");
  if (with_seed)
    whole_number(cmd->add_option(
        "--seed", seed,
        "seed of every random choice (default: the config's seed, " + std::to_string(Config{}.seed) + ")"));
}

Config ConfigOptions::make() const {
  Config c;
  if (!file.empty()) {
    config_load_file(c, file);
    try {
      config_validate(c);
    } catch (const Error& e) {
      throw Error(file + ": " + e.what());
    }
  }
  // Only the command line is left to break a rule: each of these is a usage error.
  try {
    for (const std::string& a : sets) config_set_assignment(c, a);
    config_validate(c);
  } catch (const Error& e) {
    const std::string what = e.what();
    throw UsageError(what.rfind("--set", 0) == 0 ? what : "--set: " + what);
  }
  if (seed) c.seed = *seed;
  return c;
}

std::vector<NamedFile> config_input_files(const ConfigOptions& options, const Config& config) {
  return {{"--config", options.file}, {"keywords=", config.graph.keywords}};
}

std::string transcript_or_none(const std::string& t) { return t == "none" ? std::string() : t; }

void check_output_extensions(const std::vector<OutputSpec>& outputs, const std::string& hint) {
  for (const OutputSpec& o : outputs)
    if (!o.path.empty() && !o.extensions.empty() &&
        std::none_of(o.extensions.begin(), o.extensions.end(),
                     [&](const std::string& e) { return ends_with_ci(o.path, e); }))
      throw UsageError(o.path + ": " + o.option + " must be a " + extension_list(o.extensions) +
                       " file (its extension chooses the format)" + hint);
}

void check_outputs(const std::vector<OutputSpec>& outputs) {
  check_output_extensions(outputs);
  for (const OutputSpec& o : outputs) check_output_file({o.option, o.path}, o.extensions);
}

void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::cerr << "gmg: warning: " << escape_nonprintable(w) << "\n";
}

void add_allow_silence_flag(CLI::App* cmd, bool& allow) {
  cmd->add_flag("--allow-silence", allow,
                "take audio that cannot be speech as it is: shorter than 0.5 s, silent (its loudest second below -60 "
                "dB full scale) or without an onset in more than 10 s (refused by default)");
}

}  // namespace gmg
