#include "engine/cli/cli.h"

#include <csignal>
#include <iostream>
#include <new>
#include <optional>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "engine/batch/batch.h"
#include "engine/cli/cli_common.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/interrupt.h"
#include "engine/core/strings.h"

namespace gmg {

namespace {

// Every --help ends with it (README "Bad input and exit codes" is the long form). The rule: 2 is
// decided from the command line's text alone, before any file is read (UsageError and CLI11's
// parse errors); 1 needs the files (engine/cli/cli_common.h).
const char* const kExitCodes =
    "Exit codes: 0 success; 2 the command line is wrong, found before any file is read (an unknown option, a value "
    "out of range or of the wrong form, options that contradict, an output whose extension names no format it "
    "writes); 1 an input file cannot be read or is refused, an output cannot be written where asked, or the work "
    "failed; batch: 1 some clip failed, 2 the batch could not start; interrupted by Ctrl-C (SIGINT) 130, by SIGTERM "
    "143, by SIGHUP 129: temporary files removed, the process ends by the signal.";

// "gmg reenact" for the subcommand the parse reached, so the hint names the right --help.
std::string command_path(const CLI::App& app) {
  std::string path = "gmg";
  for (const CLI::App* a = &app; a && !a->get_subcommands().empty();) {
    a = a->get_subcommands().front();
    path += " " + a->get_name();
  }
  return path;
}

std::vector<CLI::App*> all_subcommands(CLI::App& app) {
  return app.get_subcommands([](CLI::App*) { return true; });
}

// The subcommand called `name`, or null (CLI11 2.1 has no lookup that does not throw).
CLI::App* subcommand_named(CLI::App& app, const std::string& name) {
  for (CLI::App* sub : all_subcommands(app))
    if (sub->check_name(name)) return sub;
  return nullptr;
}

// "--graph", "-o", ...: every name an option of cmd answers to.
std::vector<std::string> option_names(const CLI::App& cmd) {
  std::vector<std::string> names;
  for (const CLI::Option* o : cmd.get_options()) {
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

bool looks_like_number(const std::string& s) { return parse_number(s).has_value(); }

// The first word of the command line that is neither an option of the subcommand it follows nor
// a value: "unknown option '--grpah' (did you mean '--graph'?)", with the subcommand's path.
// nullopt when every option is known (the parse error is then CLI11's own).
std::optional<std::string> unknown_option(CLI::App& app, int argc, char** argv) {
  CLI::App* cmd = &app;
  std::string path = "gmg";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    if (cmd == &app && !arg.empty() && arg[0] != '-') {
      CLI::App* sub = subcommand_named(app, arg);
      if (sub == nullptr) return std::nullopt;  // handled by unknown_command
      cmd = sub;
      path += " " + arg;
      continue;
    }
    if (arg.size() < 2 || arg[0] != '-' || looks_like_number(arg)) continue;  // a value
    std::string name = arg.substr(0, arg.find('='));
    if (name.size() > 2 && name[1] != '-') name = name.substr(0, 2);  // -j4: -j with its value
    if (cmd->get_option_no_throw(name) != nullptr) continue;
    if (cmd != &app && app.get_option_no_throw(name) != nullptr) continue;  // --help, --version
    std::string message = cmd == &app ? std::string() : cmd->get_name() + ": ";
    message += "unknown option '" + escape_nonprintable(name) + "'";
    message += did_you_mean(name, option_names(*cmd));
    message += " (see '" + path + " --help')";
    return message;
  }
  return std::nullopt;
}

// "unknown command 'biuld' (did you mean 'build'?)" when the first word names no subcommand.
std::optional<std::string> unknown_command(CLI::App& app, int argc, char** argv) {
  if (argc < 2) return std::nullopt;
  const std::string first = argv[1];
  if (first.empty() || first[0] == '-' || subcommand_named(app, first) != nullptr) return std::nullopt;
  std::vector<std::string> names;
  for (const CLI::App* sub : all_subcommands(app)) names.push_back(sub->get_name());
  return "unknown command '" + escape_nonprintable(first) + "'" + did_you_mean(first, names) +
         " (see 'gmg --help' for the commands)";
}

void print_error(const std::string& message) { std::cerr << "gmg: error: " << escape_nonprintable(message) << "\n"; }

// Prints the message, removes what the job left and ends the process by the signal (the contract
// of engine/core/interrupt.h).
[[noreturn]] void die_interrupted(const Interrupted& e) {
  print_error(e.what());
  std::cout.flush();
  remove_temporaries_and_die(e.signal_number());
  std::abort();  // not reached: the signal's default action ends the process
}

}  // namespace

int cli_main(int argc, char** argv) {
  CLI::App app{
      "gmg: gesture motion graphs - reenact a speaker's gestures for new speech.\n"
      "Build a graph from reference clips (motion + speech + optional transcript), then reenact new speech."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "gmg 0.1.0");
  // Subcommands copy these option defaults when they are added, so every --help shows defaults.
  app.option_defaults()->always_capture_default();
  app.footer(kExitCodes);
  int exit_code = 0;  // set by subcommands with their own codes (batch)
  add_build_command(app);
  add_inspect_command(app);
  add_reenact_command(app);
  add_evaluate_command(app);
  add_batch_command(app, &exit_code);
  add_ablation_command(app);
  add_synth_command(app);
  add_config_command(app);
  add_render_command(app);
  add_analyse_command(app);
  add_convert_command(app);
  for (CLI::App* sub : all_subcommands(app)) {
    sub->footer(kExitCodes);
    // A repeatable option's empty default would print as "=[]": nothing worth showing.
    for (CLI::Option* o : sub->get_options())
      if (o->get_default_str() == "[]") o->default_str("");
  }

  // Every subcommand: an interrupt removes the temporary files of outputs being written (batch and
  // render add their own graceful first-signal handling on top).
  const InterruptCleanup interrupt_cleanup("gmg");
  // Which subcommand ran, for the one error that cannot name a file.
  auto command = [&app] {
    const auto subs = app.get_subcommands();
    return subs.empty() ? std::string() : subs.front()->get_name() + ": ";
  };
  if (const std::optional<std::string> bad = unknown_command(app, argc, argv)) {
    print_error(*bad);
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version: printed on stdout
    if (const std::optional<std::string> bad = unknown_option(app, argc, argv)) {
      print_error(*bad);
      return 2;
    }
    print_error(std::string(e.what()) + " (see '" + command_path(app) + " --help')");
    return 2;
  } catch (const Interrupted& e) {
    die_interrupted(e);
  } catch (const UsageError& e) {
    print_error(e.what());
    return 2;
  } catch (const Error& e) {
    print_error(e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    print_error(command() + "out of memory");
    return 1;
  } catch (const std::length_error& e) {
    print_error(command() + "out of memory (" + e.what() + ")");
    return 1;
  } catch (const std::exception& e) {
    print_error(e.what());
    return 1;
  }
  return exit_code;
}

}  // namespace gmg
