// Motion files by format: BVH, or SMPL-X .npz with a BVH as skeleton template (engine/motion/npz.h).
// The command-line tool reads and writes every motion through these.
#pragma once

#include <string>
#include <vector>

#include "engine/motion/motion.h"
#include "engine/motion/npz.h"

namespace gmg {

// True when `path` ends in .npz (ASCII case-insensitive).
bool is_npz_path(const std::string& path);

// Reads a motion. An .npz path, or any file that starts like a zip archive, is read as SMPL-X
// .npz with the skeleton of the BVH `skeleton_template` (required for it: an .npz has no bone
// lengths); anything else is a BVH, and `skeleton_template` is not used. Errors as bvh_read and
// npz_read, plus "path: ... needs a skeleton template" and the template's own. With out_body,
// the .npz's body (shape, face) is read too; a BVH has none (out_body is cleared).
Motion motion_read(const std::string& path, const std::string& skeleton_template = "", SmplxBody* out_body = nullptr);

// The motion formats motion_write writes, by extension: {".bvh", ".npz"}.
extern const std::vector<std::string> kMotionWriteExtensions;

// Writes m as .npz (with `body` and `floats`, engine/motion/npz.h) when `path` ends in .npz, as
// BVH, which has no body, when it ends in .bvh (both atomically; ASCII case-insensitive). Any
// other extension is a gmg::Error naming the path, so BVH text never lands in "out.txt" or
// "x.fbx" (check_output_file with kMotionWriteExtensions refuses it before any work).
void motion_write(const std::string& path, const Motion& m, const SmplxBody& body = {},
                  NpzFloats floats = NpzFloats::Beat2);

// `gmg convert`: a motion file in another format, BVH <-> SMPL-X .npz (or the same format again).
struct ConvertOptions {
  std::string skeleton;  // BVH skeleton template of an .npz input; "" = none
  std::string betas;     // an .npz with `betas`, or an .npy: the output's body shape; "" = the input's
  NpzFloats floats = NpzFloats::Beat2;
};

struct ConvertSummary {
  int frames = 0, joints = 0;
  double fps = 0;
  std::vector<std::string> notes;  // what the output format cannot hold, or holds as zeros
};

// Reads `in` (motion_read, with its body) and writes `out` (motion_write). What is exact: BVH ->
// npz -> BVH with NpzFloats::Float64 gives the BVH's bytes back when gmg chose its Euler angles
// (any BVH gmg writes from rotations: a reenactment, a conversion from .npz) and its only position
// channels are the root's; a file's own angles come back as the same rotations (1e-6 rad), as
// another Euler solution where the file keeps one near gimbal lock that is not the continuous
// one. With Beat2 floats every rotation is kept to float32's rounding (< 3e-7 rad) and the root
// unchanged. npz -> BVH -> npz keeps every pose and `trans` to the BVH's six decimals (rotations
// within 1e-6 rad, positions within 1e-6 m) and the frame rate exactly, while a BVH holds no
// body: the face and shape are lost. ConvertSummary's notes say what the output cannot hold.
// Errors as motion_read and motion_write, and gmg::Error when out is in (check_outputs_apart).
ConvertSummary motion_convert(const std::string& in, const std::string& out, const ConvertOptions& options);

}  // namespace gmg
