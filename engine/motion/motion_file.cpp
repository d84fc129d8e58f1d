// Motion files by format: the extension decides, and the zip signature catches an archive
// under another name (which the BVH reader would only call "not a BVH file").
#include "engine/motion/motion_file.h"

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "engine/motion/bvh.h"
#include "engine/motion/npz.h"

namespace gmg {

bool is_npz_path(const std::string& path) { return ends_with_ci(path, ".npz"); }

Motion motion_read(const std::string& path, const std::string& skeleton_template) {
  const std::string bytes = read_file_bytes(path);
  const bool zip_signature = bytes.compare(0, 4, "PK\x03\x04", 4) == 0;
  if (!is_npz_path(path) && !zip_signature) return bvh_parse(bytes, path);
  if (skeleton_template.empty())
    throw Error(path + ": an SMPL-X .npz motion has joint rotations but no bone lengths; it needs a skeleton " +
                "template, a BVH of the same joints (--skeleton template.bvh)");
  if (is_npz_path(skeleton_template))
    throw Error(skeleton_template + ": a skeleton template must be a BVH file, not an .npz");
  return npz_parse(bytes, path, bvh_read(skeleton_template).skeleton);
}

void motion_write(const std::string& path, const Motion& m) {
  if (is_npz_path(path))
    npz_write(path, m);
  else
    bvh_write(path, m);
}

}  // namespace gmg
