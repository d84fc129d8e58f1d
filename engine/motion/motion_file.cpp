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

Motion motion_read(const std::string& path, const std::string& skeleton_template, SmplxBody* out_body) {
  if (out_body) *out_body = SmplxBody();
  if (!is_npz_path(path) && !starts_like_zip(path)) return bvh_read(path);
  if (skeleton_template.empty())
    throw Error(path + ": an SMPL-X .npz motion has joint rotations but no bone lengths; it needs a skeleton " +
                "template, a BVH of the same joints (--skeleton template.bvh)");
  if (is_npz_path(skeleton_template))
    throw Error(skeleton_template + ": a skeleton template must be a BVH file, not an .npz");
  return npz_read(path, bvh_read(skeleton_template).skeleton, out_body, skeleton_template);
}

const std::vector<std::string> kMotionWriteExtensions = {".bvh", ".npz"};

void motion_write(const std::string& path, const Motion& m, const SmplxBody& body, NpzFloats floats) {
  check_output_file({"", path}, kMotionWriteExtensions);
  if (is_npz_path(path))
    npz_write(path, m, body, floats);
  else
    bvh_write(path, m);
}

ConvertSummary motion_convert(const std::string& in, const std::string& out, const ConvertOptions& options) {
  check_outputs_apart({{"OUT", out}}, {{"IN", in}, {"--skeleton", options.skeleton}, {"--betas", options.betas}});
  check_output_file({"OUT", out}, kMotionWriteExtensions);  // before any work
  const std::vector<double> betas = options.betas.empty() ? std::vector<double>() : read_betas_file(options.betas);
  SmplxBody body;
  const Motion m = motion_read(in, options.skeleton, &body);
  if (!options.betas.empty()) body.betas = betas;
  ConvertSummary s;
  s.frames = m.frame_count;
  s.joints = m.joint_count();
  s.fps = m.fps;
  if (is_npz_path(out)) {
    bool joint_positions = false;
    for (std::size_t j = 1; j < m.skeleton.joints.size(); ++j)
      for (Channel c : m.skeleton.joints[j].channels) joint_positions = joint_positions || is_position_channel(c);
    if (joint_positions)
      s.notes.push_back(in +
                        " has position channels on joints other than the root: an .npz holds the root's "
                        "translation only, so they come back as the joints' offsets");
    if (has_smplx_names(m.skeleton) && !body.has_face())
      s.notes.push_back(in + " has no face: the .npz's expressions are zeros");
    if (has_smplx_names(m.skeleton) && body.betas.empty())
      s.notes.push_back(in + " has no body shape: the .npz's betas are zeros (--betas FILE gives them)");
  } else if (body.has_face() || !body.betas.empty()) {
    s.notes.push_back(out + ": a BVH holds no body: the face and shape of " + in + " are not kept");
  }
  motion_write(out, m, body, options.floats);
  return s;
}

}  // namespace gmg
