#include "engine/app/cli.h"

#include <filesystem>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>

#include "engine/app/ablation/ablation.h"
#include "engine/app/batch/batch.h"
#include "engine/motion/bvh.h"
#include "engine/core/error.h"
#include "engine/app/evaluate_files.h"
#include "engine/core/files.h"
#include "engine/app/pipeline.h"
#include "engine/app/synth/synth.h"
#include "graph/graph_io.h"
#include "graph/stats.h"

namespace gmg {
namespace {

// --config FILE and --set key=value, shared by the subcommands that take parameters.
struct ConfigOptions {
  std::string file;
  std::vector<std::string> sets;
  std::optional<std::uint64_t> seed;

  void add(CLI::App* cmd, bool with_seed) {
    cmd->add_option("--config", file, "JSON file of parameters (see 'gmg config')");
    cmd->add_option("--set", sets, "parameter override key=value (repeatable)");
    if (with_seed) cmd->add_option("--seed", seed, "seed of every random choice");
  }
  Config make() const {
    Config c = config_from(file, sets);
    if (seed) c.seed = *seed;
    return c;
  }
};

text::TranscriptFormat format_from(const std::string& name) { return text::parse_transcript_format(name); }

// "none" (or empty) means the clip has no transcript.
std::string transcript_or_none(const std::string& t) { return t == "none" ? std::string() : t; }

void write_json_file(const std::string& path, const nlohmann::ordered_json& j) {
  const std::string text = j.dump(2) + "\n";
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
}

std::pair<int, int> parse_range(const std::string& text, int frames) {
  if (text.empty()) return {0, frames};
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) throw Error("--frames expects FROM:TO, got '" + text + "'");
  try {
    const int from = colon == 0 ? 0 : std::stoi(text.substr(0, colon));
    const int to = colon + 1 == text.size() ? frames : std::stoi(text.substr(colon + 1));
    return {from, to};
  } catch (const std::exception&) {
    throw Error("--frames expects FROM:TO with whole numbers, got '" + text + "'");
  }
}

}  // namespace

int cli_main(int argc, char** argv) {
  CLI::App app{"gmg: gesture motion graphs - reenact a speaker's gestures for new speech.\n"
               "Build a graph from reference clips (BVH + WAV + optional transcript), then reenact new speech."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "gmg 0.1.0");
  int exit_code = 0;

  // ---- build ----
  auto* build = app.add_subcommand("build", "build a motion graph from one or more reference clips");
  std::vector<std::string> build_motion, build_audio, build_transcript;
  std::string build_out, build_format = "auto";
  ConfigOptions build_cfg;
  build->add_option("--motion", build_motion, "reference motion BVH (repeat per clip)")->required();
  build->add_option("--audio", build_audio, "its speech WAV (repeat per clip, in the same order)")->required();
  build->add_option("--transcript", build_transcript,
                    "its transcript (.tsv, .TextGrid, .json) or 'none' (repeat per clip when given)");
  build->add_option("--transcript-format", build_format, "auto, tsv, textgrid or json");
  build->add_option("-o,--output", build_out, "graph file to write")->required();
  build_cfg.add(build, false);
  build->callback([&] {
    if (build_motion.size() != build_audio.size())
      throw Error("build: " + std::to_string(build_motion.size()) + " --motion but " + std::to_string(build_audio.size()) +
                  " --audio: give one audio per motion, in the same order");
    if (!build_transcript.empty() && build_transcript.size() != build_motion.size())
      throw Error("build: give one --transcript per clip (write '--transcript none' for a clip without one)");
    const Config cfg = build_cfg.make();
    std::vector<ReferenceFiles> clips;
    for (std::size_t i = 0; i < build_motion.size(); ++i)
      clips.push_back({build_motion[i],
                       {build_audio[i], build_transcript.empty() ? "" : transcript_or_none(build_transcript[i]),
                        format_from(build_format)}});
    const MotionGraph g = graph_build_from_files(clips, cfg);
    graph_save(build_out, g);
    const GraphStats s = graph_stats(g);
    std::cout << "wrote " << build_out << ": " << s.frames << " frames, " << s.onset_nodes << " onset, "
              << s.keyword_nodes << " keyword, " << s.break_nodes << " break nodes, " << s.unnatural_edges
              << " transitions\n";
  });

  // ---- inspect ----
  auto* inspect = app.add_subcommand("inspect", "print the counts of a built graph; export DOT/GraphML");
  std::string inspect_graph, inspect_dot, inspect_graphml, inspect_frames;
  bool inspect_json = false;
  inspect->add_option("graph", inspect_graph, "graph file")->required();
  inspect->add_flag("--json", inspect_json, "print one JSON object");
  inspect->add_option("--dot", inspect_dot, "write GraphViz DOT of the frame range");
  inspect->add_option("--graphml", inspect_graphml, "write GraphML of the frame range");
  inspect->add_option("--frames", inspect_frames, "frame range FROM:TO for the exports (default: all)");
  inspect->callback([&] {
    const MotionGraph g = graph_load(inspect_graph);
    const GraphStats s = graph_stats(g);
    nlohmann::ordered_json j = {{"frames", s.frames},
                                {"clips", s.clips},
                                {"fps", g.motion.fps},
                                {"joints", g.motion.joint_count()},
                                {"onset nodes", s.onset_nodes},
                                {"keyword nodes", s.keyword_nodes},
                                {"break nodes", s.break_nodes},
                                {"key nodes", s.key_nodes},
                                {"natural edges", s.natural_edges},
                                {"unnatural edges", s.unnatural_edges},
                                {"mean out-degree", s.mean_out_degree},
                                {"frames with a transition", s.share_with_transition},
                                {"shortest subsequence", s.shortest_subsequence},
                                {"longest subsequence", s.longest_subsequence}};
    if (inspect_json) {
      std::cout << j.dump() << "\n";
    } else {
      for (auto it = j.begin(); it != j.end(); ++it) std::cout << it.key() << ": " << it.value().dump() << "\n";
      for (const ClipInfo& c : g.clips)
        std::cout << "clip: " << c.name << " (frames " << c.first_frame << ".." << c.first_frame + c.frame_count - 1 << ")\n";
    }
    const auto [from, to] = parse_range(inspect_frames, g.frame_count());
    if (!inspect_dot.empty()) graph_write_dot(inspect_dot, g, from, to);
    if (!inspect_graphml.empty()) graph_write_graphml(inspect_graphml, g, from, to);
  });

  // ---- reenact ----
  auto* re = app.add_subcommand("reenact", "generate gestures for new speech");
  std::string re_graph, re_audio, re_transcript, re_out, re_report, re_format = "auto";
  std::string re_ref_motion, re_ref_audio, re_ref_transcript;
  ConfigOptions re_cfg;
  re->add_option("--graph", re_graph, "graph file from 'gmg build'");
  re->add_option("--reference-motion", re_ref_motion, "instead of --graph: reference BVH (graph built in memory)");
  re->add_option("--reference-audio", re_ref_audio, "the reference's WAV");
  re->add_option("--reference-transcript", re_ref_transcript, "the reference's transcript (optional)");
  re->add_option("--audio", re_audio, "the new speech (WAV)")->required();
  re->add_option("--transcript", re_transcript, "its transcript (.tsv, .TextGrid, .json; optional)");
  re->add_option("--transcript-format", re_format, "auto, tsv, textgrid or json");
  re->add_option("-o,--output", re_out, "BVH to write")->required();
  re->add_option("--report", re_report, "JSON report to write");
  re_cfg.add(re, true);
  re->callback([&] {
    if (re_graph.empty() == re_ref_motion.empty())
      throw Error("reenact: give either --graph or --reference-motion with --reference-audio");
    const Config cfg = re_cfg.make();
    MotionGraph g;
    std::string graph_name = re_graph;
    if (!re_graph.empty()) {
      g = graph_load(re_graph);
    } else {
      if (re_ref_audio.empty()) throw Error("reenact: --reference-motion needs --reference-audio");
      g = graph_build_from_files({{re_ref_motion, {re_ref_audio, transcript_or_none(re_ref_transcript), text::TranscriptFormat::Auto}}}, cfg);
      graph_name = re_ref_motion;
    }
    const Reenactment r = reenact(g, {re_audio, transcript_or_none(re_transcript), format_from(re_format)}, cfg, graph_name);
    bvh_write(re_out, r.motion);
    if (!re_report.empty()) write_json_file(re_report, r.report);
    const auto& t = r.report["totals"];
    std::cout << "wrote " << re_out << ": " << r.motion.frame_count << " frames, " << t["subsequences"] << " subsequences, "
              << t["accepted"] << " accepted, fallbacks " << t["fallbacks"].dump() << ", failures " << t["failures"] << "\n";
  });

  // ---- evaluate ----
  auto* ev = app.add_subcommand("evaluate", "objective metrics of a generated motion");
  EvaluateInputs ev_in;
  EvaluateOptions ev_opts;
  bool ev_json = false;
  std::string ev_out, ev_hist = "overflow";
  ev->add_option("--generated", ev_in.generated, "generated BVH")->required();
  ev->add_option("--truth", ev_in.truth, "ground-truth BVH (same skeleton and length)");
  ev->add_option("--audio", ev_in.audio, "the speech WAV (beat consistency and speech correlation, with a control)");
  ev->add_option("--report", ev_in.report, "the reenactment report (failures, fallbacks, transitions, junctions)");
  ev->add_option("--reference", ev_in.reference,
                 "the reference capture, BVH or graph (.gmg): jump threshold, and ratios when there is no truth");
  ev->add_flag("--trim", ev_in.trim, "cut the longer of generated and truth to the shorter (with a warning)");
  ev->add_option("--hellinger", ev_hist, "speed histogram bins: overflow (ours) or genea")
      ->check(CLI::IsMember({"overflow", "genea"}))
      ->capture_default_str();
  ev->add_option("--hist-width", ev_opts.metrics.hist_bin_width, "histogram bin width, cm/s")->capture_default_str();
  ev->add_option("--plot", ev_in.plot, "draw speeds, onset strength, onsets and junctions over time (.png or .svg)");
  ev->add_flag("--json", ev_json, "print one JSON object on standard output");
  ev->add_option("-o,--output", ev_out, "also write the JSON to this file");
  ev->callback([&] {
    ev_opts.metrics.hist_bins = *enum_from_name(kHistogramBinsNames, ev_hist);
    const EvaluateResult r = evaluate_files(ev_in, ev_opts);
    for (const std::string& w : r.warnings) std::cerr << "gmg: warning: " << w << "\n";
    if (!ev_out.empty()) write_json_file(ev_out, r.json);
    std::cout << (ev_json ? r.json.dump() : r.json.dump(2)) << "\n";
  });

  // ---- batch ----
  add_batch_command(app, &exit_code);

  // ---- ablation ----
  auto* abl = app.add_subcommand("ablation",
                                 "the paper's Table 2 with baselines: time folds of one recording, seven setups");
  std::string abl_motion, abl_audio, abl_transcript, abl_csv, abl_hist = "overflow";
  AblationOptions abl_opts;
  int abl_seeds = 5;
  ConfigOptions abl_cfg;
  abl->add_option("--motion", abl_motion, "recording's BVH")->required();
  abl->add_option("--audio", abl_audio, "its WAV")->required();
  abl->add_option("--transcript", abl_transcript, "its transcript (optional)");
  abl->add_option("--folds", abl_opts.folds, "time folds: each K-th is the test part once (>= 2)")->capture_default_str();
  abl->add_option("--seeds", abl_seeds, "seeds per setup and fold (1..)")->check(CLI::PositiveNumber)->capture_default_str();
  abl->add_option("--hellinger", abl_hist, "speed histogram bins: overflow (ours) or genea")
      ->check(CLI::IsMember({"overflow", "genea"}))
      ->capture_default_str();
  abl->add_option("--hist-width", abl_opts.metrics.hist_bin_width, "histogram bin width, cm/s")->capture_default_str();
  abl->add_option("--csv", abl_csv, "also write the table as CSV");
  abl_cfg.add(abl, false);
  abl->callback([&] {
    abl_opts.seeds.clear();
    for (int i = 0; i < abl_seeds; ++i) abl_opts.seeds.push_back(static_cast<std::uint64_t>(i + 1));
    abl_opts.metrics.hist_bins = *enum_from_name(kHistogramBinsNames, abl_hist);
    const AblationResult result =
        ablation_run({abl_motion, abl_audio, transcript_or_none(abl_transcript)}, abl_opts, abl_cfg.make());
    std::cout << ablation_markdown(result);
    if (!abl_csv.empty()) {
      const std::string csv = ablation_csv(result);
      write_file_atomically(abl_csv, [&](std::ostream& os) { os << csv; });
    }
  });

  // ---- synth ----
  auto* syn = app.add_subcommand("synth", "write a procedural speaker clip (BVH + WAV + TSV) for demos and tests");
  SynthSpec spec;
  std::string syn_dir, syn_stem = "synth";
  bool syn_no_motion = false;
  syn->add_option("-o,--output", syn_dir, "folder to write into")->required();
  syn->add_option("--stem", syn_stem, "file name stem");
  syn->add_option("--duration", spec.duration_s, "seconds")->check(CLI::PositiveNumber);
  syn->add_option("--seed", spec.seed, "seed");
  syn->add_option("--style", spec.style, "speaker style 0..1")->check(CLI::Range(0.0, 1.0));
  syn->add_option("--joints", spec.joint_count_hint, "joint count hint (0 = default skeleton)");
  syn->add_flag("--no-motion", syn_no_motion, "write only the speech (WAV + TSV), as a test input");
  syn->callback([&] {
    const SynthClip clip = synth_speaker(spec);
    synth_write(clip, syn_dir, syn_stem);
    if (syn_no_motion) std::filesystem::remove(std::filesystem::path(syn_dir) / (syn_stem + ".bvh"));
    std::cout << "wrote " << syn_dir << "/" << syn_stem << (syn_no_motion ? ".{wav,tsv}" : ".{bvh,wav,tsv}") << ": "
              << spec.duration_s << " s, " << clip.words.size() << " words\n";
  });

  // ---- config ----
  auto* cfg_cmd = app.add_subcommand("config", "print every parameter with its value (JSON, usable as --config)");
  ConfigOptions cfg_opts;
  bool cfg_keys = false;
  cfg_opts.add(cfg_cmd, true);
  cfg_cmd->add_flag("--keys", cfg_keys, "list the keys with a line of help each");
  cfg_cmd->callback([&] {
    const Config c = cfg_opts.make();
    if (cfg_keys) {
      for (const ConfigKey& k : config_keys()) std::cout << k.name << " = " << config_get(c, k.name) << "  # " << k.help << "\n";
    } else {
      std::cout << config_to_json(c) << "\n";
    }
  });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const Error& e) {
    std::cerr << "gmg: error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "gmg: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "gmg: error: " << e.what() << "\n";
    return 1;
  }
  return exit_code;
}

}  // namespace gmg
