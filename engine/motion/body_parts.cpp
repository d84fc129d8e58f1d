#include "engine/motion/body_parts.h"

#include <algorithm>

#include "engine/core/strings.h"

namespace gmg {
namespace {

bool names_a_foot(const std::string& name) {
  const std::string n = ascii_lower(name);
  return n.find("ankle") != std::string::npos || n.find("foot") != std::string::npos;
}

int parent_of(const Skeleton& s, int j) { return s.joints[static_cast<std::size_t>(j)].parent; }

// Whether no ancestor of j satisfies `is`.
template <typename Is>
bool topmost(const Skeleton& s, int j, const Is& is) {
  for (int k = parent_of(s, j); k >= 0; k = parent_of(s, k))
    if (is(s.joints[static_cast<std::size_t>(k)].name)) return false;
  return true;
}

}  // namespace

std::vector<Leg> find_legs(const Skeleton& s) {
  std::vector<Leg> legs;
  for (int j = 0; j < s.joint_count(); ++j) {
    if (!names_a_foot(s.joints[static_cast<std::size_t>(j)].name) || !topmost(s, j, names_a_foot)) continue;
    Leg leg;
    leg.ankle = j;
    leg.knee = parent_of(s, j);
    leg.hip = leg.knee >= 0 ? parent_of(s, leg.knee) : -1;
    if (leg.hip < 0 || parent_of(s, leg.hip) < 0) continue;
    leg.length = glm::length(s.joints[static_cast<std::size_t>(leg.knee)].offset) +
                 glm::length(s.joints[static_cast<std::size_t>(leg.ankle)].offset);
    if (leg.length > 0.0) legs.push_back(leg);
  }
  if (legs.size() != 2) legs.clear();
  return legs;
}

std::vector<int> wrist_joints(const Skeleton& skeleton) {
  std::vector<int> out;
  for (int j = 0; j < skeleton.joint_count(); ++j)
    if (ascii_lower(skeleton.joints[static_cast<std::size_t>(j)].name).find("wrist") != std::string::npos)
      out.push_back(j);
  if (out.empty())
    for (int j = 0; j < skeleton.joint_count(); ++j)
      if (ends_with_ci(skeleton.joints[static_cast<std::size_t>(j)].name, "hand")) out.push_back(j);
  return out;
}

int jaw_joint(const Skeleton& skeleton) {
  int found = -1, count = 0;
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    const std::string name = ascii_lower(skeleton.joints[static_cast<std::size_t>(j)].name);
    if (name == "jaw") return j;
    if (name.find("jaw") != std::string::npos) {
      found = j;
      ++count;
    }
  }
  return count == 1 ? found : -1;
}

std::vector<int> upper_body_joints(const Skeleton& s) {
  std::vector<int> ends = wrist_joints(s);
  auto names_head = [](const std::string& name) { return ascii_lower(name).find("head") != std::string::npos; };
  for (int j = 0; j < s.joint_count(); ++j)
    if (names_head(s.joints[static_cast<std::size_t>(j)].name) && topmost(s, j, names_head)) {
      ends.push_back(j);
      break;
    }
  std::vector<char> in(static_cast<std::size_t>(s.joint_count()), 0);
  if (!ends.empty()) {
    for (int e : ends)
      for (int k = e; k > 0; k = parent_of(s, k)) in[static_cast<std::size_t>(k)] = 1;
  } else {
    std::vector<char> leg(in.size(), 0);
    for (const Leg& l : find_legs(s)) leg[static_cast<std::size_t>(l.hip)] = 1;
    for (int j = 1; j < s.joint_count(); ++j) {
      const int p = parent_of(s, j);
      if (p >= 0 && leg[static_cast<std::size_t>(p)]) leg[static_cast<std::size_t>(j)] = 1;
      in[static_cast<std::size_t>(j)] = !leg[static_cast<std::size_t>(j)];
    }
  }
  std::vector<int> out;
  for (int j = 1; j < s.joint_count(); ++j)
    if (in[static_cast<std::size_t>(j)]) out.push_back(j);
  return out;
}

}  // namespace gmg
