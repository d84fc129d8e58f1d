// `gmg convert`: a motion between BVH and SMPL-X .npz (engine/motion/motion_file.h motion_convert).
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/cli/cli_common.h"
#include "engine/core/enum_names.h"
#include "engine/core/error.h"
#include "engine/motion/motion_file.h"

namespace gmg {
namespace {

struct ConvertArgs {
  std::string in, out, floats = "beat2";
  ConvertOptions options;
};

void run_convert(ConvertArgs& a) {
  if (!a.options.skeleton.empty() && !is_npz_path(a.in))
    throw UsageError("convert: --skeleton gives an .npz input its bones; " + a.in + " is not an .npz");
  check_output_extensions({{"OUT", a.out, kMotionWriteExtensions}});
  a.options.floats = *enum_from_name(kNpzFloatsNames, a.floats);
  const ConvertSummary s = motion_convert(a.in, a.out, a.options);
  for (const std::string& n : s.notes) std::cerr << "gmg: note: " << n << "\n";
  std::cout << "wrote " << a.out << ": " << s.frames << " frames at " << s.fps << " fps, " << s.joints << " joints\n";
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "convert", "convert a motion between BVH and SMPL-X .npz (BEAT2's layout), by the files' extensions");
  auto a = std::make_shared<ConvertArgs>();
  cmd->add_option("IN", a->in, "the motion to read: BVH, or SMPL-X .npz with --skeleton")->required();
  cmd->add_option("OUT", a->out, "the motion to write: .bvh or .npz")->required();
  cmd->add_option("--skeleton", a->options.skeleton, "BVH whose hierarchy gives an .npz input its skeleton");
  cmd->add_option("--betas", a->options.betas,
                  "an .npz with `betas` (or an .npy): the body shape an .npz output gets (default: the input's)");
  cmd->add_option("--npz-dtype", a->floats,
                  "beat2 (poses and betas float32, as BEAT2 ships them) or float64 (a BVH -> npz -> BVH round trip "
                  "gives the BVH's bytes back)")
      ->check(CLI::IsMember({"beat2", "float64"}))
      ->capture_default_str();
  cmd->callback([a] { run_convert(*a); });
}

}  // namespace gmg
