// `gmg config`: every parameter with its value.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/cli/cli_common.h"

namespace gmg {
namespace {

struct ConfigArgs {
  ConfigOptions config;
  bool keys = false;
};

void run_config(const ConfigArgs& a) {
  const Config c = a.config.make();
  if (a.keys) {
    for (const ConfigKey& k : config_keys())
      std::cout << k.name << " = " << config_get(c, k.name) << "  # " << k.help << "\n";
  } else {
    std::cout << config_to_json(c) << "\n";
  }
}

}  // namespace

void add_config_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("config", "print every parameter with its value (JSON, usable as --config)");
  auto a = std::make_shared<ConfigArgs>();
  a->config.add(cmd, true);
  cmd->add_flag("--keys", a->keys, "list the keys with a line of help each");
  cmd->callback([a] { run_config(*a); });
}

}  // namespace gmg
