// The synthetic speaker's skeleton: an upper body with legs, then (for a larger joint count
// hint) finger chains, face joints and an accessory chain.
#include <algorithm>
#include <string>

#include "engine/core/error.h"
#include "engine/synth/synth_internal.h"

namespace gmg {
namespace {

using namespace synth_internal;
using V = glm::dvec3;

struct Node {
  std::string name;
  int parent = -1;
  glm::dvec3 offset{0.0};
  glm::dvec3 tip{0.0};  // End Site offset when the node ends up a leaf
  std::vector<int> children;
};

struct Tree {
  std::vector<Node> nodes;
  int add(const std::string& name, int parent, glm::dvec3 offset, glm::dvec3 tip) {
    Node n;
    n.name = name;
    n.parent = parent;
    n.offset = offset;
    n.tip = tip;
    nodes.push_back(n);
    const int id = static_cast<int>(nodes.size()) - 1;
    if (parent >= 0) nodes[static_cast<std::size_t>(parent)].children.push_back(id);
    return id;
  }
  int find(const std::string& name) const {
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].name == name) return static_cast<int>(i);
    return -1;
  }
  int size() const { return static_cast<int>(nodes.size()); }
};

// Depth-first, so every joint follows its parent (the BVH order).
void flatten(const Tree& tree, int node, int parent_index, Skeleton& out) {
  const Node& n = tree.nodes[static_cast<std::size_t>(node)];
  Joint j;
  j.name = n.name;
  j.parent = parent_index;
  j.offset = n.offset;
  j.rotation_order = {2, 0, 1};
  if (parent_index < 0)
    j.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition,
                  Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  else
    j.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  j.has_end_site = n.children.empty();
  if (j.has_end_site) j.end_site = n.tip;
  out.joints.push_back(j);
  const int me = out.joint_count() - 1;
  for (int c : n.children) flatten(tree, c, me, out);
}

// The 22 joints of the default skeleton; Hips is node 0.
void add_body(Tree& t) {
  const int hips = t.add("Hips", -1, V(0, 95, 0), V(0, 10, 0));
  const int spine = t.add("Spine", hips, V(0, 10, 0), V(0, 12, 0));
  const int spine1 = t.add("Spine1", spine, V(0, 12, 0), V(0, 12, 0));
  const int spine2 = t.add("Spine2", spine1, V(0, 12, 0), V(0, 12, 0));
  const int neck = t.add("Neck", spine2, V(0, 16, 0), V(0, 10, 0));
  t.add("Head", neck, V(0, 10, 0), V(0, 18, 0));
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? 1.0 : -1.0;  // Left is +X (the character faces +Z)
    const std::string p = side == 0 ? "Left" : "Right";
    const int sh = t.add(p + "Shoulder", spine2, V(3 * s, 10, 0), V(14 * s, 0, 0));
    const int arm = t.add(p + "Arm", sh, V(14 * s, 0, 0), V(28 * s, 0, 0));
    const int fore = t.add(p + "ForeArm", arm, V(28 * s, 0, 0), V(25 * s, 0, 0));
    t.add(p + "Hand", fore, V(25 * s, 0, 0), V(18 * s, 0, 0));
  }
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? 1.0 : -1.0;
    const std::string p = side == 0 ? "Left" : "Right";
    const int up = t.add(p + "UpLeg", hips, V(9 * s, -5, 0), V(0, -42, 0));
    const int leg = t.add(p + "Leg", up, V(0, -42, 0), V(0, -42, 0));
    const int foot = t.add(p + "Foot", leg, V(0, -42, 0), V(0, -6, 13));
    t.add(p + "ToeBase", foot, V(0, -6, 13), V(0, 0, 6));
  }
}

// Finger chains, one segment level at a time (so a hint in between gives every finger of both
// hands the same depth where possible), until the tree has `want` nodes.
void add_fingers(Tree& t, int want) {
  const double seg_len[4] = {4.0, 2.6, 2.0, 1.6};
  for (int level = 0; level < 4; ++level) {
    for (int f = 0; f < 5; ++f) {
      for (int side = 1; side >= 0; --side) {  // Right first: it is the dominant hand
        if (t.size() >= want) break;
        const double s = side == 0 ? 1.0 : -1.0;
        const std::string p = side == 0 ? "Left" : "Right";
        const std::string name = p + "Hand" + kFingers[f] + std::to_string(level + 1);
        // Finger direction in the hand's frame (hand along +-X, palm down, thumb forward).
        const V dir = f == 4 ? glm::normalize(V(0.6 * s, -0.2, 0.8)) : V(s, 0, 0);
        const int parent = level == 0 ? t.find(p + "Hand") : t.find(p + "Hand" + kFingers[f] + std::to_string(level));
        V offset;
        if (level == 0) {
          const double z[5] = {2.5, 0.7, -1.1, -2.8, 2.8};
          const double x[5] = {9.0, 9.2, 8.8, 8.2, 2.5};
          offset = V(x[f] * s, f == 4 ? -1.0 : 0.0, z[f]);
        } else {
          offset = dir * seg_len[level - 1] * (f == 4 ? 0.9 : (f == 3 ? 0.8 : 1.0));
        }
        const double tip_len = level < 3 ? seg_len[level] : 1.2;
        t.add(name, parent, offset, dir * tip_len);
      }
    }
  }
}

// Then face joints, then an accessory chain behind the back (any length), up to `want` nodes.
void add_face_and_accessories(Tree& t, int want) {
  const int head = t.find("Head");
  if (t.size() < want) t.add("Jaw", head, V(0, 2, 3), V(0, -3, 7));
  if (t.size() < want) t.add("LeftEye", head, V(3.2, 8, 8), V(0, 0, 1.5));
  if (t.size() < want) t.add("RightEye", head, V(-3.2, 8, 8), V(0, 0, 1.5));
  int prev = t.find("Spine2");
  for (int k = 1; t.size() < want; ++k)
    prev = t.add("Accessory" + std::to_string(k), prev, k == 1 ? V(0, 6, -10) : V(0, -3, -1.5), V(0, -3, -1.5));
}

}  // namespace

Skeleton synth_skeleton(int joint_count_hint) {
  if (joint_count_hint < 0 || joint_count_hint > kMaxJoints)
    throw Error("synth_skeleton: joint_count_hint " + std::to_string(joint_count_hint) + " outside 0.." +
                std::to_string(kMaxJoints));
  Tree t;
  add_body(t);
  const int want = std::max(joint_count_hint, t.size());
  add_fingers(t, want);
  add_face_and_accessories(t, want);
  Skeleton sk;
  flatten(t, 0, -1, sk);
  return sk;
}

}  // namespace gmg
