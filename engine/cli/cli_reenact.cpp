// `gmg reenact`: gestures for new speech, from a built graph or one built in memory.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/cli/cli_common.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/npz.h"
#include "engine/pipeline/pipeline.h"
#include "graph/graph_io.h"
#include "graph/stats.h"

namespace gmg {
namespace {

struct ReenactArgs {
  std::string graph, audio, transcript, output, report, format = "auto";
  std::string ref_motion, ref_audio, ref_transcript, skeleton, tier, betas, keep;
  std::vector<std::string> ranges, pins, word_pins;
  ConfigOptions config;
  bool allow_silence = false;
};

void run_reenact(const ReenactArgs& a) {
  if (a.graph.empty() == a.ref_motion.empty())
    throw UsageError("reenact: give either --graph or --reference-motion with --reference-audio");
  if (a.graph.empty() && a.ref_audio.empty()) throw UsageError("reenact: --reference-motion needs --reference-audio");
  check_output_extensions({{"-o", a.output, kMotionWriteExtensions}, {"--report", a.report, kJsonExtensions}});
  const Config cfg = a.config.make();
  std::vector<NamedFile> inputs = {{"--graph", a.graph},
                                   {"--reference-motion", a.ref_motion},
                                   {"--reference-audio", a.ref_audio},
                                   {"--reference-transcript", transcript_or_none(a.ref_transcript)},
                                   {"--audio", a.audio},
                                   {"--transcript", transcript_or_none(a.transcript)},
                                   {"--skeleton", a.skeleton},
                                   {"--betas", a.betas},
                                   {"--keep", a.keep}};
  for (const NamedFile& f : config_input_files(a.config, cfg)) inputs.push_back(f);
  check_outputs_apart({{"-o", a.output}, {"--report", a.report}}, inputs);
  check_outputs({{"-o", a.output, kMotionWriteExtensions}, {"--report", a.report, kJsonExtensions}});
  Control control;
  try {  // a malformed value is a usage error, as CLI11's own
    for (const std::string& p : a.pins) control.pins.push_back(parse_pin(p, "--pin", false));
    for (const std::string& p : a.word_pins) control.pins.push_back(parse_pin(p, "--pin-word", true));
    for (const std::string& r : a.ranges) control.ranges.push_back(parse_range(r, "--range"));
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (a.keep.empty() != control.ranges.empty()) throw UsageError("reenact: --keep and --range go together");
  if (!a.word_pins.empty() && a.transcript.empty()) throw UsageError("reenact: --pin-word needs --transcript");
  // Read first: a bad file stops the command before the long work.
  const std::vector<double> betas = a.betas.empty() ? std::vector<double>() : read_betas_file(a.betas);
  OutputTransaction outputs;  // the BVH and the report, both or neither
  MotionGraph g;
  std::string graph_name = a.graph;
  std::vector<std::string> warnings;
  if (!a.graph.empty()) {
    g = graph_load(a.graph, MotionCheck::OnUse);  // the motion is checked where it is played
    const std::string lock_note = check_lock_joints_of_graph(g, cfg, a.graph);
    if (!lock_note.empty()) warnings.push_back(lock_note);
  } else {
    g = graph_build_from_files(
        {{a.ref_motion,
          {a.ref_audio, transcript_or_none(a.ref_transcript), text::TranscriptFormat::Auto, a.tier, a.allow_silence},
          a.skeleton}},
        cfg, {}, 1, &warnings);
    graph_name = a.ref_motion;
  }
  print_warnings(warnings);
  Motion kept;
  SmplxBody kept_face;
  if (!a.keep.empty()) {
    kept = is_npz_path(a.keep) ? npz_read(a.keep, g.motion.skeleton, &kept_face) : motion_read(a.keep);
    control.keep = &kept;
    control.keep_body = &kept_face;
    control.keep_name = a.keep;
  }
  Reenactment r = reenact(
      g, {a.audio, transcript_or_none(a.transcript), text::parse_transcript_format(a.format), a.tier, a.allow_silence},
      cfg, graph_name, control);
  print_warnings(r.warnings);
  if (!a.betas.empty()) reenactment_use_betas(r, betas, a.betas);
  motion_write(a.output, r.motion, r.body);
  if (!a.report.empty()) write_json_file(a.report, r.report);
  outputs.commit();
  const auto& t = r.report["totals"];
  std::cout << "wrote " << a.output << ": " << r.motion.frame_count << " frames, " << t["subsequences"]
            << " subsequences, " << t["accepted"] << " accepted, fallbacks " << t["fallbacks"].dump() << ", failures "
            << t["failures"] << "\n";
}

}  // namespace

void add_reenact_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("reenact", "generate gestures for new speech");
  auto a = std::make_shared<ReenactArgs>();
  cmd->add_option("--graph", a->graph, "graph file from 'gmg build'");
  cmd->add_option("--reference-motion", a->ref_motion,
                  "instead of --graph: reference BVH or SMPL-X .npz (graph built in memory)");
  cmd->add_option("--reference-audio", a->ref_audio, "the reference's speech (WAV, FLAC, MP3, ...)");
  cmd->add_option("--reference-transcript", a->ref_transcript, "the reference's transcript (optional)");
  cmd->add_option("--audio", a->audio, "the new speech (WAV, FLAC, MP3, OGG, M4A, ...)")->required();
  cmd->add_option("--transcript", a->transcript, "its transcript (.tsv, .TextGrid, .json; optional)");
  transcript_format_check(
      cmd->add_option("--transcript-format", a->format, "auto, tsv, textgrid or json (Google, Whisper, WhisperX)"));
  cmd->add_option("--tier", a->tier, "TextGrid tier of the words (default: 'words', else the only interval tier)");
  cmd->add_option("--skeleton", a->skeleton, "BVH whose hierarchy gives an .npz --reference-motion its skeleton");
  cmd->add_option("--betas", a->betas,
                  "an .npz with `betas` (or an .npy) whose body shape an .npz output gets (default: the reference's)");
  cmd->add_option("-o,--output", a->output,
                  "motion to write: .bvh, or .npz (SMPL-X as BEAT2 ships it, with the reference's shape and face)")
      ->required();
  cmd->add_option("--report", a->report, "JSON report to write (.json)");
  cmd->add_option("--keep", a->keep,
                  "an earlier output (.bvh or .npz) for this audio: keep every frame outside --range");
  cmd->add_option("--range", a->ranges, "FROM:TO seconds of --keep to plan afresh (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--pin", a->pins,
                  "T=FROM:TO: at T s play the reference from FROM to TO s (graph timeline), or T=CLIP@FROM:TO "
                  "(repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--pin-word", a->word_pins,
                  "N=FROM:TO: the same where the transcript's word N (from 0) starts (repeatable)")
      ->allow_extra_args(false);
  add_allow_silence_flag(cmd, a->allow_silence);
  a->config.add(cmd, true);
  cmd->callback([a] { run_reenact(*a); });
}

}  // namespace gmg
