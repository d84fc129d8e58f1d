// Motion files by format: BVH, or SMPL-X .npz with a BVH as skeleton template (engine/motion/npz.h).
// The command-line tool reads and writes every motion through these.
#pragma once

#include <string>
#include <vector>

#include "engine/motion/motion.h"

namespace gmg {

// True when `path` ends in .npz (ASCII case-insensitive).
bool is_npz_path(const std::string& path);

// Reads a motion. An .npz path, or any file that starts like a zip archive, is read as SMPL-X
// .npz with the skeleton of the BVH `skeleton_template` (required for it: an .npz has no bone
// lengths); anything else is a BVH, and `skeleton_template` is not used. Errors as bvh_read and
// npz_read, plus "path: ... needs a skeleton template" and the template's own.
Motion motion_read(const std::string& path, const std::string& skeleton_template = "");

// The motion formats motion_write writes, by extension: {".bvh", ".npz"}.
extern const std::vector<std::string> kMotionWriteExtensions;

// Writes m as .npz when `path` ends in .npz, as BVH when it ends in .bvh (both atomically; ASCII
// case-insensitive). Any other extension is a gmg::Error naming the path, so BVH text never
// lands in "out.txt" or "x.fbx" (check_output_file with kMotionWriteExtensions refuses it
// before any work).
void motion_write(const std::string& path, const Motion& m);

}  // namespace gmg
