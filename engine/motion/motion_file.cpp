// Motion files by format: the extension decides, and the zip signature catches an archive
// under another name (which the BVH reader would only call "not a BVH file").
#include "engine/motion/motion_file.h"

#include <fstream>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "engine/motion/bvh.h"
#include "engine/motion/npz.h"

namespace gmg {

namespace {

// True when the file starts with a zip local header. A file that cannot be opened is left to the
// reader, whose error says why.
bool starts_like_zip(const std::string& path) {
  check_input_file(path);  // a FIFO or a device must not be opened (the open could block)
  std::ifstream in(path, std::ios::binary);
  char head[4] = {0, 0, 0, 0};
  return in.read(head, 4) && std::string(head, 4) == std::string("PK\x03\x04", 4);
}

}  // namespace

bool is_npz_path(const std::string& path) { return ends_with_ci(path, ".npz"); }

Motion motion_read(const std::string& path, const std::string& skeleton_template) {
  if (!is_npz_path(path) && !starts_like_zip(path)) return bvh_read(path);
  if (skeleton_template.empty())
    throw Error(path + ": an SMPL-X .npz motion has joint rotations but no bone lengths; it needs a skeleton " +
                "template, a BVH of the same joints (--skeleton template.bvh)");
  if (is_npz_path(skeleton_template))
    throw Error(skeleton_template + ": a skeleton template must be a BVH file, not an .npz");
  return npz_read(path, bvh_read(skeleton_template).skeleton);
}

const std::vector<std::string> kMotionWriteExtensions = {".bvh", ".npz"};

void motion_write(const std::string& path, const Motion& m) {
  check_output_file({"", path}, kMotionWriteExtensions);
  if (is_npz_path(path))
    npz_write(path, m);
  else
    bvh_write(path, m);
}

}  // namespace gmg
