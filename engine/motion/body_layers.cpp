#include "engine/motion/body_layers.h"

#include <algorithm>
#include <limits>

#include "engine/core/error.h"
#include "engine/core/strings.h"

namespace gmg {
namespace {

std::vector<std::vector<int>> children_of(const Skeleton& s) {
  std::vector<std::vector<int>> out(static_cast<std::size_t>(s.joint_count()));
  for (int j = 1; j < s.joint_count(); ++j)
    out[static_cast<std::size_t>(s.joints[static_cast<std::size_t>(j)].parent)].push_back(j);
  return out;
}

// World positions of every joint in frame 0.
std::vector<glm::dvec3> first_frame_positions(const Motion& m) {
  std::vector<glm::dquat> rot;
  std::vector<glm::dvec3> pos;
  motion_world_pose(m, 0, rot, pos);
  return pos;
}

// The joints from the root down to j, root first.
std::vector<int> chain(const Skeleton& s, int j) {
  std::vector<int> c;
  for (int k = j; k >= 0; k = s.joints[static_cast<std::size_t>(k)].parent) c.push_back(k);
  std::reverse(c.begin(), c.end());
  return c;
}

int common_ancestor(const Skeleton& s, int a, int b) {
  const std::vector<int> ca = chain(s, a), cb = chain(s, b);
  int last = 0;
  for (std::size_t i = 0; i < std::min(ca.size(), cb.size()) && ca[i] == cb[i]; ++i) last = ca[i];
  return last;
}

void mark_subtree(const std::vector<std::vector<int>>& children, int j, std::vector<char>& out) {
  out[static_cast<std::size_t>(j)] = 1;
  for (int c : children[static_cast<std::size_t>(j)]) mark_subtree(children, c, out);
}

// The child of `ancestor` on the chain to j.
int child_towards(const Skeleton& s, int ancestor, int j) {
  int k = j;
  while (s.joints[static_cast<std::size_t>(k)].parent != ancestor) k = s.joints[static_cast<std::size_t>(k)].parent;
  return k;
}

// From `from` upwards while a joint has exactly one child: the spine up to and including the chest.
std::vector<int> spine_from(const std::vector<std::vector<int>>& children, int from) {
  std::vector<int> out;
  for (int k = from;;) {
    out.push_back(k);
    const std::vector<int>& c = children[static_cast<std::size_t>(k)];
    if (c.size() != 1) break;
    k = c.front();
  }
  return out;
}

// A leg's joints: the subtree of the hip branch's child towards the foot, in file order.
std::vector<int> leg_joints(const Skeleton& s, const std::vector<std::vector<int>>& children, int branch, int foot) {
  std::vector<char> in(static_cast<std::size_t>(s.joint_count()), 0);
  mark_subtree(children, child_towards(s, branch, foot), in);
  std::vector<int> out;
  for (int j = 0; j < s.joint_count(); ++j)
    if (in[static_cast<std::size_t>(j)]) out.push_back(j);
  return out;
}

}  // namespace

BodyLayers find_body_layers(const Motion& m) {
  const Skeleton& s = m.skeleton;
  BodyLayers out;
  if (s.joint_count() < 4) return out;
  const std::vector<std::vector<int>> children = children_of(s);
  const std::vector<glm::dvec3> pos = first_frame_positions(m);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const glm::dvec3& p : pos) {
    lo = std::min(lo, p.y);
    hi = std::max(hi, p.y);
  }
  const double height = hi - lo;
  if (!(height > 0.0)) return out;
  // End joints, lowest first.
  std::vector<int> ends;
  for (int j = 1; j < s.joint_count(); ++j)
    if (children[static_cast<std::size_t>(j)].empty()) ends.push_back(j);
  std::sort(ends.begin(), ends.end(), [&](int a, int b) {
    return pos[static_cast<std::size_t>(a)].y < pos[static_cast<std::size_t>(b)].y ||
           (pos[static_cast<std::size_t>(a)].y == pos[static_cast<std::size_t>(b)].y && a < b);
  });
  if (ends.size() < 2 || pos[static_cast<std::size_t>(ends[0])].y > lo + 0.1 * height) return out;
  const int first = ends[0];
  for (std::size_t i = 1; i < ends.size(); ++i) {
    const int second = ends[i];
    if (pos[static_cast<std::size_t>(second)].y > lo + 0.1 * height) break;
    const int branch = common_ancestor(s, first, second);
    // Two toes of one foot part at the ankle; the feet part at the hips, a third of the way up.
    if (pos[static_cast<std::size_t>(branch)].y < lo + height / 3.0) continue;
    out.hip_branch = branch;
    out.legs[0] = leg_joints(s, children, branch, first);
    out.legs[1] = leg_joints(s, children, branch, second);
    out.feet = {first, second};
    break;
  }
  if (out.hip_branch < 0) return BodyLayers{};
  out.lower.assign(static_cast<std::size_t>(s.joint_count()), 0);
  for (int k : chain(s, out.hip_branch)) out.lower[static_cast<std::size_t>(k)] = 1;
  for (const std::vector<int>& leg : out.legs)
    for (int j : leg) out.lower[static_cast<std::size_t>(j)] = 1;
  // The spine starts at the hip branch's upper child: the one whose subtree reaches highest.
  int upper = -1;
  double top = -std::numeric_limits<double>::infinity();
  for (int c : children[static_cast<std::size_t>(out.hip_branch)]) {
    if (out.lower[static_cast<std::size_t>(c)]) continue;
    std::vector<char> in(static_cast<std::size_t>(s.joint_count()), 0);
    mark_subtree(children, c, in);
    for (int j = 0; j < s.joint_count(); ++j)
      if (in[static_cast<std::size_t>(j)] && pos[static_cast<std::size_t>(j)].y > top) {
        top = pos[static_cast<std::size_t>(j)].y;
        upper = c;
      }
  }
  if (upper >= 0) out.spine = spine_from(children, upper);
  return out;
}

BodyLayers body_layers_from_names(const Motion& m, const std::vector<std::string>& names) {
  const Skeleton& s = m.skeleton;
  std::vector<std::string> all;
  for (const Joint& j : s.joints) all.push_back(j.name);
  BodyLayers out = find_body_layers(m);
  std::vector<char> lower(static_cast<std::size_t>(s.joint_count()), 0);
  for (const std::string& n : names) {
    const int j = s.find(n);
    if (j < 0)
      throw Error("lower_joints names '" + n + "', which is not a joint of the skeleton" + did_you_mean(n, all));
    lower[static_cast<std::size_t>(j)] = 1;
  }
  if (!lower[0]) throw Error("lower_joints must include the root joint '" + s.joints[0].name + "'");
  out.lower = std::move(lower);
  // The spine: from the lower joint whose upper child carries the most joints (the chest, arms
  // and head hang from it), upwards. Not the deepest such joint: a toe left out of the names is an
  // upper child of its foot.
  const std::vector<std::vector<int>> children = children_of(s);
  std::vector<int> subtree(static_cast<std::size_t>(s.joint_count()), 1);
  for (int j = s.joint_count() - 1; j > 0; --j)
    subtree[static_cast<std::size_t>(s.joints[static_cast<std::size_t>(j)].parent)] +=
        subtree[static_cast<std::size_t>(j)];
  out.spine.clear();
  out.hip_branch = -1;
  int best = 0, best_child = -1;
  for (int j = 0; j < s.joint_count(); ++j) {
    if (!out.lower[static_cast<std::size_t>(j)]) continue;
    for (int c : children[static_cast<std::size_t>(j)])
      if (!out.lower[static_cast<std::size_t>(c)] && subtree[static_cast<std::size_t>(c)] > best) {
        best = subtree[static_cast<std::size_t>(c)];
        out.hip_branch = j;
        best_child = c;
      }
  }
  if (best_child >= 0) out.spine = spine_from(children, best_child);
  const std::vector<glm::dvec3> pos = first_frame_positions(m);
  out.feet.clear();
  for (std::vector<int>& leg : out.legs) {
    leg.erase(std::remove_if(leg.begin(), leg.end(), [&](int j) { return !out.lower[static_cast<std::size_t>(j)]; }),
              leg.end());
    if (leg.empty()) continue;
    int lowest = leg.front();
    for (int j : leg)
      if (pos[static_cast<std::size_t>(j)].y < pos[static_cast<std::size_t>(lowest)].y) lowest = j;
    out.feet.push_back(lowest);
  }
  return out;
}

std::string describe_body_layers(const Skeleton& s, const BodyLayers& layers) {
  if (!layers.layered()) return "one layer (no two legs found)";
  std::string lower, spine;
  for (int j = 0; j < s.joint_count(); ++j)
    if (layers.lower[static_cast<std::size_t>(j)])
      lower += (lower.empty() ? "" : " ") + s.joints[static_cast<std::size_t>(j)].name;
  for (int j : layers.spine) spine += (spine.empty() ? "" : " ") + s.joints[static_cast<std::size_t>(j)].name;
  return "lower: " + lower + "; spine: " + spine;
}

}  // namespace gmg
