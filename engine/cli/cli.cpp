#include "engine/cli/cli.h"

#include <iostream>
#include <new>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "engine/batch/batch.h"
#include "engine/cli/cli_common.h"
#include "engine/core/error.h"
#include "engine/core/files.h"

namespace gmg {

namespace {

// "gmg reenact" for the subcommand the parse reached, so the hint names the right --help.
std::string command_path(const CLI::App& app) {
  std::string path = "gmg";
  for (const CLI::App* a = &app; a && !a->get_subcommands().empty();) {
    a = a->get_subcommands().front();
    path += " " + a->get_name();
  }
  return path;
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
  app.footer(
      "Exit codes: 0 success, 1 an input or processing error, 2 a usage error (batch: 1 some clip failed, 2 a "
      "setup error, 130 interrupted).");
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
  // A repeatable option's empty default would print as "=[]": nothing worth showing.
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    for (CLI::Option* o : sub->get_options())
      if (o->get_default_str() == "[]") o->default_str("");

  // Every subcommand: an interrupt removes the temporary files of outputs being written (batch adds
  // its own graceful first-signal handling on top).
  const InterruptCleanup interrupt_cleanup;
  // Which subcommand ran, for the one error that cannot name a file.
  auto command = [&app] {
    const auto subs = app.get_subcommands();
    return subs.empty() ? std::string() : subs.front()->get_name() + ": ";
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version: printed on stdout
    std::cerr << "gmg: error: " << e.what() << " (see '" << command_path(app) << " --help')\n";
    return 2;
  } catch (const UsageError& e) {
    std::cerr << "gmg: error: " << e.what() << "\n";
    return 2;
  } catch (const Error& e) {
    std::cerr << "gmg: error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "gmg: error: " << command() << "out of memory\n";
    return 1;
  } catch (const std::length_error& e) {
    std::cerr << "gmg: error: " << command() << "out of memory (" << e.what() << ")\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "gmg: error: " << e.what() << "\n";
    return 1;
  }
  return exit_code;
}

}  // namespace gmg
