// `gmg build`: a motion graph from one or more reference clips.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/app/cli_common.h"
#include "engine/app/pipeline.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "graph/graph_io.h"
#include "graph/stats.h"

namespace gmg {
namespace {

struct BuildArgs {
  std::vector<std::string> motion, audio, transcript;
  std::string output, format = "auto", skeleton, tier;
  ConfigOptions config;
};

void run_build(const BuildArgs& a) {
  if (a.motion.size() != a.audio.size())
    throw UsageError("build: " + std::to_string(a.motion.size()) + " --motion but " + std::to_string(a.audio.size()) +
                     " --audio: give one audio per motion, in the same order");
  if (!a.transcript.empty() && a.transcript.size() != a.motion.size())
    throw UsageError("build: give one --transcript per clip (write '--transcript none' for a clip without one)");
  const Config cfg = a.config.make();
  std::vector<NamedFile> inputs = config_input_files(a.config, cfg);
  for (const std::string& m : a.motion) inputs.push_back({"--motion", m});
  for (const std::string& w : a.audio) inputs.push_back({"--audio", w});
  for (const std::string& t : a.transcript) inputs.push_back({"--transcript", transcript_or_none(t)});
  check_outputs_apart({{"-o", a.output}}, inputs);
  std::vector<ReferenceFiles> clips;
  for (std::size_t i = 0; i < a.motion.size(); ++i)
    clips.push_back({a.motion[i],
                     {a.audio[i], a.transcript.empty() ? "" : transcript_or_none(a.transcript[i]),
                      text::parse_transcript_format(a.format), a.tier},
                     a.skeleton});
  const MotionGraph g = graph_build_from_files(clips, cfg);
  graph_save(a.output, g);
  const GraphStats s = graph_stats(g);
  std::cout << "wrote " << a.output << ": " << s.frames << " frames, " << s.onset_nodes << " onset, " << s.keyword_nodes
            << " keyword, " << s.break_nodes << " break nodes, " << s.unnatural_edges << " transitions\n";
}

}  // namespace

void add_build_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("build", "build a motion graph from one or more reference clips");
  auto a = std::make_shared<BuildArgs>();
  cmd->add_option("--motion", a->motion, "reference motion: BVH, or SMPL-X .npz with --skeleton (repeat per clip)")
      ->required();
  cmd->add_option("--audio", a->audio, "its speech: WAV, FLAC, MP3, OGG, M4A, ... (repeat per clip, in the same order)")
      ->required();
  cmd->add_option("--transcript", a->transcript,
                  "its transcript (.tsv, .TextGrid, .json) or 'none' (repeat per clip when given)");
  cmd->add_option("--transcript-format", a->format, "auto, tsv, textgrid or json (Google, Whisper, WhisperX)");
  cmd->add_option("--tier", a->tier, "TextGrid tier of the words (default: 'words', else the only interval tier)");
  cmd->add_option("--skeleton", a->skeleton, "BVH whose hierarchy gives .npz motions their skeleton");
  cmd->add_option("-o,--output", a->output, "graph file to write")->required();
  a->config.add(cmd, false);
  cmd->callback([a] { run_build(*a); });
}

}  // namespace gmg
