// SMPL-X .npz motion: the arrays of npy.h mapped onto a template skeleton.
#include "engine/motion/npz.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "engine/motion/npy.h"
#include "engine/motion/zip.h"

namespace gmg {
namespace {

constexpr int kSmplxJoints = 55;
// Limits of the body's arrays: far above any body model (SMPL-X: 300 betas, 100 expressions;
// FLAME: 400), far below what would exhaust memory.
constexpr std::uint64_t kMaxBetas = 10000, kMaxExpressionDims = 10000;

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

// An optional text array (gender, model): "" when absent or not a text numpy wrote as str (some
// archives store bytes or objects there; the body is still usable without its label).
std::string optional_text(const ZipReader& zip, const std::string& key, const std::string& name) {
  if (!zip.has(key + ".npy")) return "";
  try {
    return npy_parse_text(zip.read(key + ".npy"), name + ": " + key + ".npy");
  } catch (const Error&) {
    return "";
  }
}

// The betas of an array: 1-D, or 1 x N as some tools save them; finite.
std::vector<double> betas_of(const NpyArray& a, const std::string& where) {
  const bool row = a.shape.size() == 2 && a.shape[0] == 1;
  if (!(a.shape.size() == 1 || row) || a.values.empty() || a.values.size() > kMaxBetas)
    throw Error(where + ": expected shape (betas,) or (1, betas), found " + shape_of(a));
  check_finite(a, a.values.size(), where);
  return a.values;
}

SmplxBody read_body(const ZipReader& zip, const std::string& name, std::uint64_t frames) {
  SmplxBody body;
  if (zip.has("betas.npy")) {
    body.betas = betas_of(member_array(zip, "betas", name), name + ": betas.npy");
    // All zeros (the mean shape) is what gmg writes for a motion without a shape: none known.
    if (std::all_of(body.betas.begin(), body.betas.end(), [](double v) { return v == 0.0; })) body.betas.clear();
  }
  if (zip.has("expressions.npy")) {
    const NpyArray e = member_array(zip, "expressions", name);
    const std::string where = name + ": expressions.npy";
    if (e.shape.size() != 2 || e.shape[0] != frames || e.shape[1] == 0 || e.shape[1] > kMaxExpressionDims)
      throw Error(where + ": expected shape (" + std::to_string(frames) + ", coefficients) to match poses, found " +
                  shape_of(e));
    check_finite(e, e.shape[1], where);
    // All zeros is no face: what gmg (and other tools) write for a motion without one.
    if (std::any_of(e.values.begin(), e.values.end(), [](double v) { return v != 0.0; })) {
      body.expression_dims = static_cast<int>(e.shape[1]);
      body.expressions = e.values;
    }
  }
  body.gender = optional_text(zip, "gender", name);
  body.model = optional_text(zip, "model", name);
  return body;
}

}  // namespace

bool has_smplx_names(const Skeleton& sk) {
  for (const std::string& n : smplx_joint_names())
    if (sk.find(n) < 0) return false;
  return true;
}

glm::dvec3 beat2_pelvis_rest() { return {0.002777, -0.383289, 0.010682}; }

glm::dvec3 npz_root_rest(const Skeleton& sk) {
  if (sk.joints.empty()) return glm::dvec3(0.0);
  const glm::dvec3 offset = sk.joints[0].offset;
  if (offset != glm::dvec3(0.0)) return offset;
  return has_smplx_names(sk) ? beat2_pelvis_rest() : glm::dvec3(0.0);
}

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

Motion npz_parse(const std::string& bytes, const std::string& name, const Skeleton& skeleton, SmplxBody* out_body,
                 const std::string& template_name) {
  const std::string templ = "the skeleton template" + (template_name.empty() ? "" : " " + template_name);
  if (skeleton.joint_count() == 0) throw Error(name + ": " + templ + " has no joints");
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
    throw Error(poses_name + ": " + std::to_string(joints) + " joints a frame, but " + templ + " has " +
                std::to_string(skeleton.joint_count()) + " joints" +
                (joints == kSmplxJoints ? " and not all 55 SMPL-X joint names" : ""));

  Motion m = motion_rest(skeleton, frame_rate(zip, name), static_cast<int>(frames));
  m.euler_hints.clear();
  const glm::dvec3 root_rest = npz_root_rest(skeleton);
  for (int f = 0; f < m.frame_count; ++f) {
    const double* row = &poses.values[static_cast<std::size_t>(f) * poses.shape[1]];
    for (int k = 0; k < joints; ++k) {
      const double* v = row + static_cast<std::ptrdiff_t>(3) * k;
      m.rotations[m.index(f, map[k])] = expmap_to_quat(glm::dvec3(v[0], v[1], v[2]));
    }
    const double* t = &trans.values[static_cast<std::size_t>(f) * 3];
    m.translations[m.index(f, 0)] = glm::dvec3(t[0], t[1], t[2]) + root_rest;
  }
  if (out_body) *out_body = read_body(zip, name, frames);
  return m;
}

Motion npz_read(const std::string& path, const Skeleton& skeleton, SmplxBody* out_body,
                const std::string& template_name) {
  return npz_parse(read_file_bytes(path), path, skeleton, out_body, template_name);
}

std::string npz_format(const Motion& m, const std::string& name, const SmplxBody& body, NpzFloats floats) {
  const Skeleton& sk = m.skeleton;
  // Exactly the SMPL-X joints: written in SMPL-X order, so body-model tools read them right.
  const bool smplx = sk.joint_count() == kSmplxJoints && has_smplx_names(sk);
  const std::vector<int> map = joint_mapping(sk, sk.joint_count());
  const auto frames = static_cast<std::uint64_t>(m.frame_count);
  const auto joints = static_cast<std::uint64_t>(map.size());
  if (body.has_face() && body.expressions.size() != frames * static_cast<std::uint64_t>(body.expression_dims))
    throw Error(name + ": the face has " +
                std::to_string(body.expressions.size() / static_cast<std::size_t>(body.expression_dims)) +
                " frames, the motion " + std::to_string(frames));
  std::vector<double> poses, trans;
  poses.reserve(frames * joints * 3);
  trans.reserve(frames * 3);
  const glm::dvec3 root_rest = npz_root_rest(sk);
  for (int f = 0; f < m.frame_count; ++f) {
    for (int j : map) {
      const glm::dvec3 v = quat_to_expmap(m.rotation(f, j));
      poses.insert(poses.end(), {v.x, v.y, v.z});
    }
    const glm::dvec3 t = m.translation(f, 0) - root_rest;
    trans.insert(trans.end(), {t.x, t.y, t.z});
  }
  const char* const small = floats == NpzFloats::Beat2 ? "<f4" : "<f8";  // BEAT2's poses and betas
  const bool whole = m.fps == std::round(m.fps) && m.fps < 2147483647.0;
  ZipMember poses_npy{"poses.npy", npy_format(small, {frames, joints * 3}, poses)};
  ZipMember trans_npy{"trans.npy", npy_format("<f8", {frames, 3}, trans)};
  ZipMember fps_npy{"mocap_frame_rate.npy", npy_format(whole ? "<i4" : "<f8", {}, {m.fps})};
  std::vector<ZipMember> members;
  if (!smplx && body.betas.empty() && !body.has_face()) {
    members = {std::move(poses_npy), std::move(trans_npy), std::move(fps_npy)};
    return zip_format(members, name);
  }
  const std::vector<double> betas = body.betas.empty() ? std::vector<double>(kBeat2Betas, 0.0) : body.betas;
  const auto dims = static_cast<std::uint64_t>(body.has_face() ? body.expression_dims : kBeat2Expressions);
  members.push_back({"betas.npy", npy_format(small, {betas.size()}, betas)});
  members.push_back(std::move(poses_npy));
  members.push_back(
      {"expressions.npy", npy_format("<f8", {frames, dims},
                                     body.has_face() ? body.expressions : std::vector<double>(frames * dims, 0.0))});
  members.push_back(std::move(trans_npy));
  members.push_back({"model.npy", npy_format_text(body.model.empty() ? "smplx2020" : body.model)});
  members.push_back({"gender.npy", npy_format_text(body.gender.empty() ? "neutral" : body.gender)});
  members.push_back(std::move(fps_npy));
  return zip_format(members, name);
}

void npz_write(const std::string& path, const Motion& m, const SmplxBody& body, NpzFloats floats) {
  motion_check_finite(m, path);
  const std::string bytes = npz_format(m, path, body, floats);
  write_file_atomically(
      path, [&](std::ostream& os) { os << bytes; }, true);
}

std::vector<double> read_betas_file(const std::string& path) {
  const std::string bytes = read_file_bytes(path);
  if (bytes.compare(0, 4, "PK\x03\x04") == 0 || ends_with_ci(path, ".npz")) {
    const ZipReader zip(bytes, path);
    if (!zip.has("betas.npy")) {
      std::string list;
      for (const std::string& n : zip.names()) list += (list.empty() ? "" : ", ") + n;
      throw Error(path + ": no 'betas' array (the archive holds: " + (list.empty() ? std::string("nothing") : list) +
                  ")");
    }
    return betas_of(member_array(zip, "betas", path), path + ": betas.npy");
  }
  return betas_of(npy_parse(bytes, path), path);
}

}  // namespace gmg
