#include "engine/cli.h"

#include <iostream>

#include <CLI/CLI.hpp>

#include "engine/error.h"

namespace gmg {

int cli_main(int argc, char** argv) {
  CLI::App app{"gmg: gesture motion graphs - reenact a speaker's gestures for new speech"};
  app.require_subcommand(1);
  app.add_subcommand("build", "build a motion graph from reference clips");
  app.add_subcommand("inspect", "print counts of a built graph, export DOT/GraphML");
  app.add_subcommand("reenact", "generate gestures for new speech from a graph");
  app.add_subcommand("batch", "reenact many test clips against a pool of references");
  app.add_subcommand("evaluate", "objective metrics of generated motion");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    std::cerr << "gmg: subcommand not implemented yet\n";
    return 2;
  } catch (const Error& e) {
    std::cerr << "gmg: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace gmg
