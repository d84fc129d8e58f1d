// BVH writing: the hierarchy as read, angles chosen per joint to stay continuous.
#include "engine/motion/bvh.h"

#include <cstdio>

#include "engine/core/files.h"
#include "engine/core/math.h"
#include "engine/core/strings.h"

namespace gmg {
namespace {

void format_joint(const Skeleton& sk, int j, int depth, std::string& out) {
  const Joint& joint = sk.joints[j];
  const std::string indent(static_cast<std::size_t>(depth), '\t');
  char buf[256];
  out += indent + (joint.parent < 0 ? "ROOT " : "JOINT ") + joint.name + "\n";
  out += indent + "{\n";
  std::snprintf(buf, sizeof buf, "%s\tOFFSET %.6f %.6f %.6f\n", indent.c_str(), joint.offset.x, joint.offset.y,
                joint.offset.z);
  out += buf;
  if (!joint.channels.empty()) {
    out += indent + "\tCHANNELS " + std::to_string(joint.channels.size());
    for (Channel c : joint.channels) out += std::string(" ") + channel_name(c);
    out += "\n";
  }
  for (int child = j + 1; child < sk.joint_count(); ++child)
    if (sk.joints[child].parent == j) format_joint(sk, child, depth + 1, out);
  if (joint.has_end_site) {
    out += indent + "\tEnd Site\n" + indent + "\t{\n";
    std::snprintf(buf, sizeof buf, "%s\t\tOFFSET %.6f %.6f %.6f\n", indent.c_str(), joint.end_site.x, joint.end_site.y,
                  joint.end_site.z);
    out += buf;
    out += indent + "\t}\n";
  }
  out += indent + "}\n";
}

}  // namespace

std::string bvh_format(const Motion& m) {
  const Skeleton& sk = m.skeleton;
  std::string out = "HIERARCHY\n";
  format_joint(sk, 0, 0, out);
  char buf[64];
  char num[kFixed6Chars];
  out += "MOTION\nFrames: " + std::to_string(m.frame_count) + "\n";
  std::snprintf(buf, sizeof buf, "Frame Time: %.8f\n", 1.0 / m.fps);
  out += buf;
  const int joints = sk.joint_count();
  std::size_t channels = 0;
  for (const Joint& joint : sk.joints) channels += joint.channels.size();
  out.reserve(out.size() + static_cast<std::size_t>(m.frame_count) * (channels * 11 + 1));  // "-12.345678 " typical
  std::vector<glm::dvec3> previous(static_cast<std::size_t>(joints), glm::dvec3(0.0));
  for (int f = 0; f < m.frame_count; ++f) {
    bool first_value = true;
    for (int j = 0; j < joints; ++j) {
      const Joint& joint = sk.joints[j];
      if (joint.channels.empty()) continue;
      const bool hinted = !m.euler_hints.empty();
      const glm::dvec3 angles =
          hinted ? quat_to_euler_matching(m.rotation(f, j), joint.rotation_order, m.euler_hints[m.index(f, j)])
                 : quat_to_euler_near(m.rotation(f, j), joint.rotation_order, previous[j]);
      previous[j] = angles;
      const glm::dvec3& t = m.translation(f, j);
      int rot_index = 0;
      for (Channel c : joint.channels) {
        const double v = is_position_channel(c) ? t[channel_axis(c)] : angles[rot_index++] / kDegToRad;
        // printf's "%.6f" without its locale and its arbitrary-precision digits (writing the values
        // was much of a short reenactment: docs/performance.md). A value that rounds to zero is written 0.000000
        // whatever its sign (-1e-9 and 1e-9 are one value in the file), so a motion that comes
        // back through another format keeps its bytes.
        if (!first_value) out += ' ';
        out.append(num, format_fixed6(v, num));
        first_value = false;
      }
    }
    out += "\n";
  }
  return out;
}

void bvh_write(const std::string& path, const Motion& m) {
  motion_check_finite(m, path);
  const std::string text = bvh_format(m);
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
}

}  // namespace gmg
