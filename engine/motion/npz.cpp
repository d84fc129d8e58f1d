// SMPL-X .npz motion: the arrays of npy.h mapped onto a template skeleton.
#include "engine/motion/npz.h"

#include <cmath>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "engine/motion/npy.h"

namespace gmg {
namespace {

constexpr int kSmplxJoints = 55;
constexpr int kBeat2Betas = 300;
constexpr int kBeat2Expressions = 100;

bool has_smplx_names(const Skeleton& sk) {
  for (const std::string& n : smplx_joint_names())
    if (sk.find(n) < 0) return false;
  return true;
}

// For each archive joint k, the skeleton joint it drives: by SMPL-X name when `archive_joints` is
// 55 and the skeleton has every SMPL-X name, else by position when the counts agree. Empty when
// neither applies.
std::vector<int> joint_mapping(const Skeleton& sk, int archive_joints) {
  std::vector<int> map;
  if (archive_joints == kSmplxJoints && has_smplx_names(sk)) {
    for (const std::string& n : smplx_joint_names()) map.push_back(sk.find(n));
    return map;
  }
  if (sk.joint_count() == archive_joints)
    for (int j = 0; j < archive_joints; ++j) map.push_back(j);
  return map;
}

// The archive member `key`.npy, with its name in errors.
NpyArray member_array(const ZipReader& zip, const std::string& key, const std::string& name) {
  const std::string member = key + ".npy";
  return npy_parse(zip.read(member), name + ": " + member);
}

[[noreturn]] void missing_array(const ZipReader& zip, const std::string& key, const std::string& name) {
  std::string list;
  for (const std::string& n : zip.names()) list += (list.empty() ? "" : ", ") + n;
  throw Error(name + ": no '" + key + "' array (an SMPL-X motion needs poses, trans and mocap_frame_rate; the " +
              "archive holds: " + (list.empty() ? std::string("nothing") : list) + ")");
}

std::string shape_of(const NpyArray& a) {
  std::string s = "(";
  for (std::size_t i = 0; i < a.shape.size(); ++i) s += (i ? ", " : "") + std::to_string(a.shape[i]);
  return s + (a.shape.size() == 1 ? ",)" : ")");
}

void check_finite(const NpyArray& a, std::size_t columns, const std::string& where) {
  for (std::size_t i = 0; i < a.values.size(); ++i)
    if (!std::isfinite(a.values[i]))
      throw Error(where + ": the value at frame " + std::to_string(i / columns) + ", column " +
                  std::to_string(i % columns) + " is not finite");
}

double frame_rate(const ZipReader& zip, const std::string& name) {
  const std::string key = zip.has("mocap_frame_rate.npy")  ? "mocap_frame_rate"
                          : zip.has("mocap_framerate.npy") ? "mocap_framerate"
                                                           : "";
  if (key.empty()) missing_array(zip, "mocap_frame_rate", name);
  const NpyArray a = member_array(zip, key, name);
  const std::string where = name + ": " + key + ".npy";
  if (a.values.size() != 1) throw Error(where + ": expected one number, found shape " + shape_of(a));
  const double fps = a.values[0];
  if (!std::isfinite(fps) || fps <= 0.0 || fps > 10000.0)
    throw Error(where + ": frame rate " + format_number(fps) + " is not a positive number of frames per second");
  return fps;
}

}  // namespace

const std::vector<std::string>& smplx_joint_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {
        "pelvis",       "left_hip",    "right_hip",       "spine1",          "left_knee",  "right_knee",  "spine2",
        "left_ankle",   "right_ankle", "spine3",          "left_foot",       "right_foot", "neck",        "left_collar",
        "right_collar", "head",        "left_shoulder",   "right_shoulder",  "left_elbow", "right_elbow", "left_wrist",
        "right_wrist",  "jaw",         "left_eye_smplhf", "right_eye_smplhf"};
    // The hands: the left's 15 joints, then the right's, fingers in this order, 3 joints each.
    for (const char* side : {"left_", "right_"})
      for (const char* finger : {"index", "middle", "pinky", "ring", "thumb"})
        for (int k = 1; k <= 3; ++k) n.push_back(std::string(side) + finger + std::to_string(k));
    return n;
  }();
  return names;
}

Motion npz_parse(const std::string& bytes, const std::string& name, const Skeleton& skeleton) {
  if (skeleton.joint_count() == 0) throw Error(name + ": the skeleton template has no joints");
  const ZipReader zip(bytes, name);
  for (const char* key : {"poses", "trans"})
    if (!zip.has(std::string(key) + ".npy")) missing_array(zip, key, name);
  const NpyArray poses = member_array(zip, "poses", name);
  const NpyArray trans = member_array(zip, "trans", name);
  const std::string poses_name = name + ": poses.npy", trans_name = name + ": trans.npy";

  if (poses.shape.size() != 2 || poses.shape[1] % 3 != 0 || poses.shape[1] == 0)
    throw Error(poses_name + ": expected shape (frames, 3 x joints), found " + shape_of(poses));
  const std::uint64_t frames = poses.shape[0];
  const int joints = static_cast<int>(poses.shape[1] / 3);
  if (frames == 0) throw Error(poses_name + ": the motion has zero frames");
  if (frames > 100000000) throw Error(poses_name + ": too many frames (" + std::to_string(frames) + ")");
  if (trans.shape.size() != 2 || trans.shape[0] != frames || trans.shape[1] != 3)
    throw Error(trans_name + ": expected shape (" + std::to_string(frames) + ", 3) to match poses, found " +
                shape_of(trans));
  check_finite(poses, poses.shape[1], poses_name);
  check_finite(trans, 3, trans_name);
  const std::vector<int> map = joint_mapping(skeleton, joints);
  if (map.empty())
    throw Error(poses_name + ": " + std::to_string(joints) + " joints a frame, but the skeleton template has " +
                std::to_string(skeleton.joint_count()) + " joints" +
                (joints == kSmplxJoints ? " and not all 55 SMPL-X joint names" : ""));

  Motion m = motion_rest(skeleton, frame_rate(zip, name), static_cast<int>(frames));
  m.euler_hints.clear();
  const glm::dvec3 root_offset = skeleton.joints[0].offset;
  for (int f = 0; f < m.frame_count; ++f) {
    const double* row = &poses.values[static_cast<std::size_t>(f) * poses.shape[1]];
    for (int k = 0; k < joints; ++k) {
      const double* v = row + static_cast<std::ptrdiff_t>(3) * k;
      m.rotations[m.index(f, map[k])] = expmap_to_quat(glm::dvec3(v[0], v[1], v[2]));
    }
    const double* t = &trans.values[static_cast<std::size_t>(f) * 3];
    m.translations[m.index(f, 0)] = glm::dvec3(t[0], t[1], t[2]) + root_offset;
  }
  return m;
}

Motion npz_read(const std::string& path, const Skeleton& skeleton) {
  return npz_parse(read_file_bytes(path), path, skeleton);
}

std::string npz_format(const Motion& m, const std::string& name) {
  const Skeleton& sk = m.skeleton;
  // Exactly the SMPL-X joints: written in SMPL-X order, so body-model tools read them right.
  const bool smplx = sk.joint_count() == kSmplxJoints && has_smplx_names(sk);
  const std::vector<int> map = joint_mapping(sk, sk.joint_count());
  const auto frames = static_cast<std::uint64_t>(m.frame_count);
  const auto joints = static_cast<std::uint64_t>(map.size());
  std::vector<double> poses, trans;
  poses.reserve(frames * joints * 3);
  trans.reserve(frames * 3);
  const glm::dvec3 root_offset = sk.joints.empty() ? glm::dvec3(0.0) : sk.joints[0].offset;
  for (int f = 0; f < m.frame_count; ++f) {
    for (int j : map) {
      const glm::dvec3 v = quat_to_expmap(m.rotation(f, j));
      poses.insert(poses.end(), {v.x, v.y, v.z});
    }
    const glm::dvec3 t = m.translation(f, 0) - root_offset;
    trans.insert(trans.end(), {t.x, t.y, t.z});
  }
  std::vector<ZipMember> members;
  members.push_back({"poses.npy", npy_format("<f8", {frames, joints * 3}, poses)});
  members.push_back({"trans.npy", npy_format("<f8", {frames, 3}, trans)});
  const bool whole = m.fps == std::round(m.fps) && m.fps < 2147483647.0;
  members.push_back({"mocap_frame_rate.npy", npy_format(whole ? "<i4" : "<f8", {}, {m.fps})});
  if (smplx) {
    members.push_back({"betas.npy", npy_format("<f8", {kBeat2Betas}, std::vector<double>(kBeat2Betas, 0.0))});
    members.push_back({"expressions.npy", npy_format("<f8", {frames, kBeat2Expressions},
                                                     std::vector<double>(frames * kBeat2Expressions, 0.0))});
    members.push_back({"gender.npy", npy_format_text("neutral")});
    members.push_back({"model.npy", npy_format_text("smplx2020")});
  }
  return zip_format(members, name);
}

void npz_write(const std::string& path, const Motion& m) {
  motion_check_finite(m, path);
  const std::string bytes = npz_format(m, path);
  write_file_atomically(
      path, [&](std::ostream& os) { os << bytes; }, true);
}

}  // namespace gmg
