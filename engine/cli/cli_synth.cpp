// `gmg synth`: a procedural speaker clip for demos and tests.
#include <filesystem>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/cli/cli_common.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"
#include "engine/synth/synth.h"

namespace gmg {
namespace {

struct SynthArgs {
  SynthSpec spec;
  std::string dir, stem = "synth";
  bool no_motion = false;
};

void run_synth(const SynthArgs& a) {
  if (a.stem.empty() || a.stem.find('/') != std::string::npos || a.stem == "." || a.stem == "..")
    throw UsageError("synth: --stem '" + a.stem + "' is not a plain file name (the files go into -o " + a.dir + ")");
  if (a.spec.duration_s > limits::kMaxAudioSeconds)
    throw UsageError("--duration: " + format_number(a.spec.duration_s) + " s is more than the day (" +
                     format_number(limits::kMaxAudioSeconds) + " s) gmg synthesises");
  check_output_folder({"-o", a.dir});
  const SynthClip clip = synth_speaker(a.spec);
  CreatedFolders folder(a.dir);  // a failed write (a full disk) leaves no empty folder
  {
    OutputTransaction outputs;  // the three files, all or none
    synth_write(clip, a.dir, a.stem);
    if (a.no_motion) outputs.discard((std::filesystem::path(a.dir) / (a.stem + ".bvh")).string());
    outputs.commit();
  }
  folder.keep();
  std::cout << "wrote " << a.dir << "/" << a.stem << (a.no_motion ? ".{wav,tsv}" : ".{bvh,wav,tsv}") << ": "
            << a.spec.duration_s << " s, " << clip.words.size() << " words\n";
}

}  // namespace

void add_synth_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("synth", "write a procedural speaker clip (BVH + WAV + TSV) for demos and tests");
  auto a = std::make_shared<SynthArgs>();
  cmd->add_option("-o,--output", a->dir, "folder to write into")->required();
  cmd->add_option("--stem", a->stem, "file name stem");
  positive_number(cmd->add_option("--duration", a->spec.duration_s, "seconds"));
  whole_number(cmd->add_option("--seed", a->spec.seed, "seed"));
  number_from_to(cmd->add_option("--style", a->spec.style, "speaker style 0..1"), 0, 1);
  whole_number(cmd->add_option("--joints", a->spec.joint_count_hint, "joint count hint (0 = default skeleton)"),
               limits::kMaxJoints);
  cmd->add_flag("--no-motion", a->no_motion, "write only the speech (WAV + TSV), as a test input");
  cmd->callback([a] { run_synth(*a); });
}

}  // namespace gmg
