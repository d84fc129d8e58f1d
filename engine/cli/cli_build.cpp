// `gmg build`: a motion graph from one or more reference clips.
#include <filesystem>
#include <iostream>
#include <memory>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "engine/batch/batch_clips.h"
#include "engine/batch/batch_progress.h"
#include "engine/cli/cli_common.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/pipeline/pipeline.h"
#include "graph/graph_io.h"
#include "graph/stats.h"

namespace gmg {
namespace {

struct BuildArgs {
  std::vector<std::string> motion, audio, transcript, clips;
  std::string output, format = "auto", progress = "auto", skeleton, tier;
  int jobs = 0;
  ConfigOptions config;
  bool allow_silence = false;
};

// The clips of --clips: folders (flat or GENEA-style bvh/ wav/ tsv/ subfolders) and CSV
// manifests (stem,bvh,wav,transcript), read as `gmg batch` reads its pool, in stem order.
std::vector<ReferenceFiles> listed_clips(const std::vector<std::string>& sources, const std::string& tier,
                                         const std::string& skeleton, bool allow_silence) {
  std::vector<std::string> dirs, manifests, notes;
  for (const std::string& s : sources) {
    std::error_code ec;
    (std::filesystem::is_directory(s, ec) ? dirs : manifests).push_back(s);
  }
  const batch::ClipMap found = batch::collect_reference_clips(dirs, manifests, notes);
  for (const std::string& n : notes) std::cerr << "build: note: " << n << "\n";
  if (found.empty())
    throw Error("build: no reference clip (a BVH and a WAV with the same stem) in " + sources.front() +
                (sources.size() > 1 ? " and the other --clips" : ""));
  std::vector<ReferenceFiles> clips;
  for (const auto& [stem, c] : found) {
    if (!c.error.empty()) throw Error("build: clip '" + stem + "' (" + c.origin + "): " + c.error);
    clips.push_back({c.bvh, {c.wav, c.transcript, text::TranscriptFormat::Auto, tier, allow_silence}, skeleton});
  }
  return clips;
}

std::vector<ReferenceFiles> clips_of(const BuildArgs& a) {
  if (!a.clips.empty()) {
    if (!a.motion.empty() || !a.audio.empty() || !a.transcript.empty())
      throw UsageError("build: give either --clips or --motion/--audio/--transcript, not both");
    return listed_clips(a.clips, a.tier, a.skeleton, a.allow_silence);
  }
  if (a.motion.empty()) throw UsageError("build: no reference given (--motion with --audio, or --clips FILE.csv|DIR)");
  if (a.motion.size() != a.audio.size())
    throw UsageError("build: " + std::to_string(a.motion.size()) + " --motion but " + std::to_string(a.audio.size()) +
                     " --audio: give one audio per motion, in the same order");
  if (!a.transcript.empty() && a.transcript.size() != a.motion.size())
    throw UsageError("build: give one --transcript per clip (write '--transcript none' for a clip without one)");
  std::vector<ReferenceFiles> clips;
  for (std::size_t i = 0; i < a.motion.size(); ++i)
    clips.push_back({a.motion[i],
                     {a.audio[i], a.transcript.empty() ? "" : transcript_or_none(a.transcript[i]),
                      text::parse_transcript_format(a.format), a.tier, a.allow_silence},
                     a.skeleton});
  return clips;
}

// "auto": one updating line on a terminal (nothing when stderr is not one); "lines": a line per
// clip read and per tenth of the analysis; "none".
BuildProgress progress_display(const std::string& mode, std::shared_ptr<batch::Progress>& out) {
  if (mode == "none" || (mode == "auto" && ::isatty(2) == 0)) return {};
  out = std::make_shared<batch::Progress>(std::cerr, mode == "auto" ? BatchProgress::Terminal : BatchProgress::Lines);
  auto last = std::make_shared<long>(-1);
  return [display = out.get(), last, lines = mode == "lines"](const std::string& stage, long done, long total) {
    if (stage == "read") {
      display->status("build: read " + std::to_string(done) + "/" + std::to_string(total) + " clips",
                      "build: read " + std::to_string(done) + "/" + std::to_string(total) + " clips");
      return;
    }
    const long percent = total > 0 ? done * 100 / total : 100;
    if (percent == *last || (lines && percent % 10 != 0 && done != total)) return;
    *last = percent;
    const std::string text =
        "build: transitions of " + std::to_string(percent) + "% of " + std::to_string(total) + " frames";
    display->status(text, text);
  };
}

void run_build(const BuildArgs& a) {
  check_output_extensions({{"-o", a.output, kGraphExtensions}});
  const std::vector<ReferenceFiles> clips = clips_of(a);
  const Config cfg = a.config.make();
  std::vector<NamedFile> inputs = config_input_files(a.config, cfg);
  for (const ReferenceFiles& c : clips) {
    inputs.push_back({"--motion", c.motion});
    inputs.push_back({"--audio", c.speech.audio});
    if (!c.speech.transcript.empty()) inputs.push_back({"--transcript", c.speech.transcript});
  }
  if (!a.skeleton.empty()) inputs.push_back({"--skeleton", a.skeleton});
  check_outputs_apart({{"-o", a.output}}, inputs);
  check_outputs({{"-o", a.output, kGraphExtensions}});
  std::shared_ptr<batch::Progress> display;
  const BuildProgress progress = progress_display(a.progress, display);
  std::vector<std::string> warnings;
  // Hours of reference keep their motion and features in temporary files beside the output.
  const std::string folder = std::filesystem::path(a.output).parent_path().string();
  const MotionGraph g = graph_build_from_files(clips, cfg, progress, a.jobs, &warnings, folder.empty() ? "." : folder);
  if (display) display->finish();
  print_warnings(warnings);
  graph_save(a.output, g);
  const GraphStats s = graph_stats(g);
  std::cout << "wrote " << a.output << ": " << s.frames << " frames";
  if (s.clips > 1) std::cout << " from " << s.clips << " clips";
  std::cout << ", " << s.onset_nodes << " onset, " << s.keyword_nodes << " keyword, " << s.break_nodes
            << " break nodes, " << s.unnatural_edges << " transitions\n";
}

}  // namespace

void add_build_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("build", "build a motion graph from one or more reference clips");
  auto a = std::make_shared<BuildArgs>();
  cmd->add_option("--motion", a->motion, "reference motion: BVH, or SMPL-X .npz with --skeleton (repeat per clip)");
  cmd->add_option("--audio", a->audio,
                  "its speech: WAV, FLAC, MP3, OGG, M4A, ... (repeat per clip, in the same order)");
  cmd->add_option("--transcript", a->transcript,
                  "its transcript (.tsv, .TextGrid, .json) or 'none' (repeat per clip when given)");
  transcript_format_check(
      cmd->add_option("--transcript-format", a->format, "auto, tsv, textgrid or json (Google, Whisper, WhisperX)"));
  cmd->add_option("--tier", a->tier, "TextGrid tier of the words (default: 'words', else the only interval tier)");
  cmd->add_option("--skeleton", a->skeleton, "BVH whose hierarchy gives .npz motions their skeleton");
  cmd->add_option("--clips", a->clips,
                  "instead of --motion/--audio: a folder of clips (BVH + WAV + optional transcript with matching "
                  "stems, flat or in bvh/ wav/ tsv/ subfolders) or a CSV manifest with header stem,bvh,wav,transcript; "
                  "repeatable; clips join in stem order");
  whole_number(cmd->add_option("--jobs,-j", a->jobs, "clips read at once (default 0: all cores)"), kMaxJobs);
  cmd->add_option("--progress", a->progress, "auto (an updating line on a terminal), lines, or none")
      ->check(CLI::IsMember({"auto", "lines", "none"}));
  cmd->add_option("-o,--output", a->output, "graph file to write (.gmg)")->required();
  add_allow_silence_flag(cmd, a->allow_silence);
  a->config.add(cmd, false);
  cmd->callback([a] { run_build(*a); });
}

}  // namespace gmg
