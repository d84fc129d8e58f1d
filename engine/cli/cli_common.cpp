#include "engine/cli/cli_common.h"

#include <CLI/CLI.hpp>

#include "engine/core/files.h"
#include "engine/core/json.h"

namespace gmg {

void ConfigOptions::add(CLI::App* cmd, bool with_seed) {
  cmd->add_option("--config", file, "JSON file of parameters (see 'gmg config')");
  cmd->add_option("--set", sets, "parameter override key=value (repeatable)");
  if (with_seed)
    cmd->add_option("--seed", seed,
                    "seed of every random choice (default: the config's seed, " + std::to_string(Config{}.seed) + ")");
}

Config ConfigOptions::make() const {
  Config c = config_from(file, sets);
  if (seed) c.seed = *seed;
  return c;
}

std::vector<NamedFile> config_input_files(const ConfigOptions& options, const Config& config) {
  return {{"--config", options.file}, {"keywords=", config.graph.keywords}};
}

std::string transcript_or_none(const std::string& t) { return t == "none" ? std::string() : t; }

}  // namespace gmg
