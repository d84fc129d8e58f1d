#include "engine/render/figure.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "engine/core/math.h"
#include "engine/core/strings.h"
#include "engine/metrics/evaluate.h"

namespace gmg::render {
namespace {

bool has_any(const std::string& lower, std::initializer_list<const char*> tokens) {
  for (const char* t : tokens)
    if (lower.find(t) != std::string::npos) return true;
  return false;
}

bool is_face(const std::string& lower) { return has_any(lower, {"eye", "jaw", "teeth", "tongue"}); }

// End points some exporters add along or after a bone ("RightForeArmEnd", "b_head_null").
bool is_helper_end(const std::string& lower) { return ends_with_ci(lower, "end") || ends_with_ci(lower, "_null"); }

bool is_head(const std::string& lower) {
  return (lower == "head" || ends_with_ci(lower, "_head") || ends_with_ci(lower, "head")) && !is_helper_end(lower);
}

// Extra points carried by joints: each is an extra joint (parent, offset in file units, no
// rotation), so forward kinematics places it. Their parents precede them, as FK requires.
struct ExtraPoint {
  int parent = 0;
  glm::dvec3 offset{0.0};
};

Motion with_extra_points(const Motion& m, const std::vector<ExtraPoint>& extras) {
  Motion out;
  out.skeleton = m.skeleton;
  out.fps = m.fps;
  out.frame_count = m.frame_count;
  for (const ExtraPoint& e : extras) {
    Joint tip;
    tip.name = "extra point";
    tip.parent = e.parent;
    tip.offset = e.offset;
    out.skeleton.joints.push_back(tip);
  }
  const int joints = out.joint_count();
  out.rotations.assign(static_cast<std::size_t>(m.frame_count) * joints, glm::dquat(1, 0, 0, 0));
  out.translations.resize(out.rotations.size());
  for (int f = 0; f < m.frame_count; ++f) {
    for (int j = 0; j < joints; ++j) {
      if (j < m.joint_count()) {
        out.rotations[out.index(f, j)] = m.rotation(f, j);
        out.translations[out.index(f, j)] = m.translation(f, j);
      } else {
        out.translations[out.index(f, j)] = out.skeleton.joints[static_cast<std::size_t>(j)].offset;
      }
    }
  }
  return out;
}

// From the person's right to their left: the mean of the left joints minus that of the right.
glm::dvec3 lateral_at(const Eigen::MatrixXd& points, int frame, const std::vector<int>& side) {
  glm::dvec3 left(0.0), right(0.0);
  int nl = 0, nr = 0;
  const std::size_t count = std::min(side.size(), static_cast<std::size_t>(points.cols() / 3));
  for (std::size_t p = 0; p < count; ++p) {
    const glm::dvec3 q(points(frame, 3 * p), points(frame, 3 * p + 1), points(frame, 3 * p + 2));
    if (side[p] > 0) left += q, ++nl;
    if (side[p] < 0) right += q, ++nr;
  }
  return nl > 0 && nr > 0 ? left / double(nl) - right / double(nr) : glm::dvec3(0.0);
}

glm::dvec3 forward_of(const glm::dvec3& lateral) {
  const glm::dvec3 forward = glm::cross(lateral, glm::dvec3(0, 1, 0));
  return glm::length(forward) > 1e-9 ? glm::normalize(forward) : glm::dvec3(0, 0, 1);
}

// Which bones to draw (see figure.h): everything but the face, helper end points, and a world
// root (a root with a single child, e.g. GENEA 2023's body_world above b_root).
void choose_bones(const Skeleton& s, const std::vector<int>& end_owner, Figure& f) {
  const int joints = s.joint_count();
  std::vector<int> children(static_cast<std::size_t>(joints), 0);
  for (const Joint& j : s.joints)
    if (j.parent >= 0) ++children[static_cast<std::size_t>(j.parent)];
  auto lower = [&](int j) { return ascii_lower(s.joints[static_cast<std::size_t>(j)].name); };
  auto skipped_joint = [&](int j) {
    const std::string n = lower(j);
    return is_face(n) || is_helper_end(n) || (n.rfind("p_", 0) == 0 && children[static_cast<std::size_t>(j)] == 0);
  };
  const bool world_root = joints > 1 && children[0] == 1;
  for (int j = 1; j < joints; ++j) {
    const int p = s.joints[static_cast<std::size_t>(j)].parent;
    if ((p == 0 && world_root) || p == f.head || skipped_joint(j)) continue;
    f.bones.push_back({p, j});
  }
  for (std::size_t e = 0; e < end_owner.size(); ++e) {
    const int j = end_owner[e];
    if (j == f.head || skipped_joint(j) || (j == 0 && world_root)) continue;
    f.bones.push_back({j, joints + static_cast<int>(e)});
  }
}

}  // namespace

double joint_radius_cm(const std::string& name) {
  const std::string n = ascii_lower(name);
  if (has_any(n, {"thumb", "index", "middle", "ring", "pinky", "finger"})) return 1.0;
  if (has_any(n, {"hand", "wrist"})) return 2.5;
  if (has_any(n, {"forearm", "elbow", "lowerarm"})) return 3.4;
  if (has_any(n, {"upleg", "thigh", "upperleg"})) return 6.5;
  if (has_any(n, {"hips", "pelvis", "spine", "chest", "root", "torso", "body"})) return 8.0;
  if (has_any(n, {"hip"})) return 6.5;
  if (has_any(n, {"knee", "leg", "shin", "calf"})) return 4.8;
  if (has_any(n, {"foot", "ankle"})) return 3.8;
  if (has_any(n, {"toe"})) return 3.0;
  if (has_any(n, {"neck"})) return 4.5;
  if (has_any(n, {"head"})) return 5.0;
  if (has_any(n, {"arm", "shoulder", "collar", "clavicle", "scap", "delt"})) return 4.2;
  return 3.5;
}

int joint_side(const std::string& name) {
  const std::string n = ascii_lower(name);
  if (n.find("left") != std::string::npos || n.rfind("l_", 0) == 0 || n.find("_l_") != std::string::npos) return 1;
  if (n.find("right") != std::string::npos || n.rfind("r_", 0) == 0 || n.find("_r_") != std::string::npos) return -1;
  return 0;
}

Figure figure_from_motion(const Motion& m) {
  Figure f;
  f.fps = m.fps;
  f.frame_count = m.frame_count;
  for (const Joint& j : m.skeleton.joints) {
    f.radius_cm.push_back(joint_radius_cm(j.name));
    f.side.push_back(joint_side(j.name));
  }
  for (int j = 0; j < m.joint_count() && f.head < 0; ++j) {
    if (is_head(ascii_lower(m.skeleton.joints[static_cast<std::size_t>(j)].name))) {
      f.head = j;
      f.head_base = m.skeleton.joints[static_cast<std::size_t>(j)].parent;
    }
  }
  if (f.head_base < 0) f.head = -1;  // a head without a neck has no direction
  std::vector<ExtraPoint> extras;
  std::vector<int> end_owner;
  for (int j = 0; j < m.joint_count(); ++j) {
    const Joint& joint = m.skeleton.joints[static_cast<std::size_t>(j)];
    if (!joint.has_end_site) continue;
    extras.push_back({j, joint.end_site});
    end_owner.push_back(j);
    f.radius_cm.push_back(0.8 * f.radius_cm[static_cast<std::size_t>(j)]);
    f.side.push_back(f.side[static_cast<std::size_t>(j)]);
  }
  const double scale = length_unit_to_cm(m.skeleton);
  if (f.head >= 0) {
    // The nose shows which way the head turns. In the rest pose every rotation is the identity,
    // so an offset along the rest pose's forward direction is the face's direction in the head's
    // own frame.
    const Eigen::MatrixXd rest = motion_forward_kinematics(motion_rest(m.skeleton, m.fps, 1));
    const glm::dvec3 forward = forward_of(lateral_at(rest, 0, f.side));
    const double r = f.head_radius_cm / scale;
    extras.push_back({f.head, glm::dvec3(0, 0.8 * r, 0) + forward * (0.95 * r)});
    f.nose = m.joint_count() + static_cast<int>(end_owner.size());
    f.radius_cm.push_back(0.22 * f.head_radius_cm);
    f.side.push_back(0);
  }
  f.points = motion_forward_kinematics(with_extra_points(m, extras)) * scale;
  choose_bones(m.skeleton, end_owner, f);
  return f;
}

glm::dvec3 figure_point(const Figure& f, int frame, int point) {
  const Eigen::Index c = 3 * static_cast<Eigen::Index>(point);
  return {f.points(frame, c), f.points(frame, c + 1), f.points(frame, c + 2)};
}

glm::dvec3 figure_head_center(const Figure& f, int frame) {
  const glm::dvec3 head = figure_point(f, frame, f.head), base = figure_point(f, frame, f.head_base);
  const glm::dvec3 d = head - base;
  const double len = glm::length(d);
  // The head joint sits at the base of the skull: the sphere's centre is a little above it.
  return len > 1e-9 ? head + d * (0.8 * f.head_radius_cm / len) : head;
}

Box figure_box(const Figure& f) {
  Box box;
  for (int t = 0; t < f.frame_count; ++t) {
    for (const Bone& b : f.bones) {
      for (int p : {b.a, b.b}) {
        const glm::dvec3 q = figure_point(f, t, p);
        const double r = f.radius_cm[static_cast<std::size_t>(p)];
        box.add(q - glm::dvec3(r)), box.add(q + glm::dvec3(r));
      }
    }
    if (f.head >= 0) {
      const glm::dvec3 c = figure_head_center(f, t), nose = figure_point(f, t, f.nose);
      box.add(c - glm::dvec3(f.head_radius_cm)), box.add(c + glm::dvec3(f.head_radius_cm));
      box.add(nose - glm::dvec3(f.radius_cm[static_cast<std::size_t>(f.nose)]));
      box.add(nose + glm::dvec3(f.radius_cm[static_cast<std::size_t>(f.nose)]));
    }
  }
  return box;
}

glm::dvec3 figure_facing(const Figure& f) {
  glm::dvec3 lateral(0.0);
  const int step = std::max(1, f.frame_count / 200);
  for (int t = 0; t < f.frame_count; t += step) lateral += lateral_at(f.points, t, f.side);
  return forward_of(lateral);
}

}  // namespace gmg::render
