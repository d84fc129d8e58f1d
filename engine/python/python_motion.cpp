// gmg.Motion and the conversions between Python objects and the engine's types.
#include <algorithm>
#include <cmath>
#include <optional>

#include <pybind11/stl.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/rotation.h"
#include "engine/python/python_types.h"

namespace gmg::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// The array as doubles, C order, with exactly `shape` (-1: any size there).
Array array_of(const py::handle& object, const std::vector<py::ssize_t>& shape, const std::string& what) {
  check_real_numbers(object, what);
  Array a = Array::ensure(object);
  if (!a) throw Error(what + ": expected an array of numbers");
  bool ok = a.ndim() == static_cast<py::ssize_t>(shape.size());
  for (std::size_t i = 0; ok && i < shape.size(); ++i)
    ok = shape[i] < 0 || a.shape(static_cast<py::ssize_t>(i)) == shape[i];
  if (!ok) {
    std::string want = "(";
    for (std::size_t i = 0; i < shape.size(); ++i)
      want += (i ? ", " : "") + (shape[i] < 0 ? std::string(i == 0 ? "frames" : "n") : std::to_string(shape[i]));
    throw Error(what + ": expected shape " + want + (shape.size() == 1 ? ",)" : ")") + ", found " + shape_text(a));
  }
  const double* p = a.data();
  for (py::ssize_t i = 0; i < a.size(); ++i)
    if (!std::isfinite(p[i])) throw Error(what + ": value " + std::to_string(i) + " is not finite");
  return a;
}

py::array_t<double> new_array(const std::vector<py::ssize_t>& shape) { return py::array_t<double>(shape); }

int frames_of(const PyMotion& m) { return m.motion.frame_count; }
int joints_of(const PyMotion& m) { return m.motion.joint_count(); }

py::array_t<double> rotations(const PyMotion& pm) {
  const Motion& m = pm.motion;
  auto out = new_array({frames_of(pm), joints_of(pm), 4});
  double* p = out.mutable_data();
  for (const glm::dquat& q : m.rotations) {
    *p++ = q.w;
    *p++ = q.x;
    *p++ = q.y;
    *p++ = q.z;
  }
  return out;
}

py::array_t<double> axis_angle(const PyMotion& pm) {
  auto out = new_array({frames_of(pm), joints_of(pm), 3});
  double* p = out.mutable_data();
  for (const glm::dquat& q : pm.motion.rotations) {
    const glm::dvec3 v = quat_to_expmap(q);
    *p++ = v.x;
    *p++ = v.y;
    *p++ = v.z;
  }
  return out;
}

py::array_t<double> translations(const PyMotion& pm) {
  auto out = new_array({frames_of(pm), joints_of(pm), 3});
  double* p = out.mutable_data();
  for (const glm::dvec3& t : pm.motion.translations) {
    *p++ = t.x;
    *p++ = t.y;
    *p++ = t.z;
  }
  return out;
}

py::array_t<double> root(const PyMotion& pm) {
  const Motion& m = pm.motion;
  auto out = new_array({frames_of(pm), 3});
  double* p = out.mutable_data();
  for (int f = 0; f < m.frame_count; ++f) {
    const glm::dvec3& t = m.translation(f, 0);
    *p++ = t.x;
    *p++ = t.y;
    *p++ = t.z;
  }
  return out;
}

py::array_t<double> positions(const PyMotion& pm) {
  Eigen::MatrixXd fk;
  {
    const py::gil_scoped_release release;
    fk = motion_forward_kinematics(pm.motion);
  }
  auto out = new_array({frames_of(pm), joints_of(pm), 3});
  auto w = out.mutable_unchecked<3>();
  for (Eigen::Index f = 0; f < fk.rows(); ++f)
    for (int j = 0; j < joints_of(pm); ++j)
      for (int c = 0; c < 3; ++c) w(f, j, c) = fk(f, 3 * j + c);
  return out;
}

py::object expressions(const PyMotion& pm) {
  if (!pm.body.has_face()) return py::none();
  auto out = new_array({frames_of(pm), pm.body.expression_dims});
  std::copy(pm.body.expressions.begin(), pm.body.expressions.end(), out.mutable_data());
  return std::move(out);
}

py::object betas(const PyMotion& pm) {
  if (pm.body.betas.empty()) return py::none();
  auto out = new_array({static_cast<py::ssize_t>(pm.body.betas.size())});
  std::copy(pm.body.betas.begin(), pm.body.betas.end(), out.mutable_data());
  return std::move(out);
}

std::vector<double> values_of(const Array& a) { return std::vector<double>(a.data(), a.data() + a.size()); }

// A frame rate as the BVH reader takes one (engine/core/limits.h).
double fps_of(const py::handle& object, const std::string& what) {
  if (py::isinstance<py::bool_>(object) || py::isinstance<py::str>(object))
    throw Error(what + ": expected a number of frames per second");
  double v = 0;
  try {
    v = py::float_(py::reinterpret_borrow<py::object>(object)).cast<double>();
  } catch (const py::error_already_set&) {
    throw Error(what + ": expected a number of frames per second");
  }
  if (!(v >= limits::kMinFps && v <= limits::kMaxFps))
    throw Error(what + ": " + format_number(v) + " is outside the " + format_number(limits::kMinFps) + " to " +
                format_number(limits::kMaxFps) + " fps gmg reads");
  return v;
}

// Quaternion (w, x, y, z) at q, element k of a (frames, joints, 4) array, scaled to length 1 (the
// rotation it stands for); one of length 0 stands for none and is refused. One of length 1 to
// rounding is kept as it is, so the arrays of a motion give back that motion bit for bit.
glm::dquat unit_quaternion(const double* q, std::size_t k, int joints) {
  const glm::dquat v(q[0], q[1], q[2], q[3]);
  const double norm = std::sqrt(glm::dot(v, v));
  if (!(norm > 1e-9))
    throw Error("rotations: the quaternion of frame " + std::to_string(k / static_cast<std::size_t>(joints)) +
                ", joint " + std::to_string(k % static_cast<std::size_t>(joints)) + " has length 0");
  return std::abs(norm - 1.0) <= 1e-12 ? v : v / norm;
}

// The skeleton of gmg.Motion(...): names and parents checked as the BVH reader checks a
// hierarchy, the root with position and rotation channels and the other joints with rotations,
// Z X Y (BEAT2's order), so a BVH written from it reads back as it.
Skeleton skeleton_of(const py::handle& names, const py::handle& parents, const Array& offsets) {
  if (py::isinstance<py::str>(names) || !py::isinstance<py::sequence>(names))
    throw Error("joint_names: expected a list of str");
  const auto count = static_cast<py::ssize_t>(py::len(names));
  if (count < 1 || count > limits::kMaxJoints)
    throw Error("joint_names: " + std::to_string(count) + " joints; gmg reads skeletons of 1 to " +
                std::to_string(limits::kMaxJoints) + " joints");
  check_real_numbers(parents, "parents");
  if (py::isinstance<py::array>(parents) && py::reinterpret_borrow<py::array>(parents).dtype().kind() == 'f')
    throw Error("parents: expected whole numbers (joint indices), got floats");
  const auto p = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(parents);
  if (!p || p.ndim() != 1 || p.shape(0) != count)
    throw Error("parents: expected shape (" + std::to_string(count) + ",), one parent per joint name");
  if (offsets.shape(0) != count)
    throw Error("offsets: expected shape (" + std::to_string(count) + ", 3), one offset per joint name");
  Skeleton sk;
  std::vector<int> depth;
  for (py::ssize_t j = 0; j < count; ++j) {
    Joint joint;
    const std::string which = "joint_names: joint " + std::to_string(j);
    joint.name = text_of(py::reinterpret_borrow<py::sequence>(names)[static_cast<py::size_t>(j)], which);
    if (joint.name.empty()) throw Error(which + " has no name");
    if (std::any_of(joint.name.begin(), joint.name.end(), [](char c) { return is_ascii_space(c) || c < 0x20; }))
      throw Error(which + ": '" + escape_nonprintable(joint.name) +
                  "' holds a space or control character, which a BVH file cannot name");
    if (sk.find(joint.name) >= 0) throw Error(which + ": duplicate joint name '" + joint.name + "'");
    const long long parent = p.data()[j];
    if (j == 0 ? parent != -1 : (parent < 0 || parent >= j))
      throw Error("parents: joint " + std::to_string(j) + " ('" + joint.name + "') has parent " +
                  std::to_string(parent) +
                  (j == 0 ? "; the root's must be -1"
                          : "; a parent comes before its child (0 to " + std::to_string(j - 1) + ")"));
    joint.parent = static_cast<int>(parent);
    depth.push_back(j == 0 ? 1 : depth[static_cast<std::size_t>(parent)] + 1);
    if (depth.back() > limits::kMaxHierarchyDepth)
      throw Error("parents: joints nested more than " + std::to_string(limits::kMaxHierarchyDepth) + " deep");
    const double* o = offsets.data() + 3 * j;
    joint.offset = glm::dvec3(o[0], o[1], o[2]);
    if (j == 0) joint.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition};
    for (Channel c : {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation}) joint.channels.push_back(c);
    joint.rotation_order = rotation_order_from_channels(joint.channels);
    sk.joints.push_back(std::move(joint));
  }
  return sk;
}

// gmg.Motion(joint_names, parents, offsets, rotations, root, fps): see its docstring.
PyMotion motion_from_arrays(const py::object& names, const py::object& parents, const py::object& offsets,
                            const py::object& rotations, const py::object& root, const py::object& fps,
                            const py::object& name) {
  const Array o = array_of(offsets, {-1, 3}, "offsets");
  PyMotion out;
  out.name = name.is_none() ? std::string() : text_of(name, "name");
  const Skeleton sk = skeleton_of(names, parents, o);
  const int joints = sk.joint_count();
  const Array r = array_of(rotations, {-1, joints, 4}, "rotations");
  const Array t = array_of(root, {-1, 3}, "root");
  const py::ssize_t frames = r.shape(0);
  if (frames < 1 || frames > limits::kMaxFrames)
    throw Error("rotations: " + std::to_string(frames) + " frames; gmg reads 1 to " +
                std::to_string(limits::kMaxFrames));
  if (t.shape(0) != frames)
    throw Error("root: " + std::to_string(t.shape(0)) + " frames, but rotations has " + std::to_string(frames));
  out.motion = motion_rest(sk, fps_of(fps, "fps"), static_cast<int>(frames));
  out.motion.euler_hints.clear();
  for (std::size_t k = 0; k < out.motion.rotations.size(); ++k)
    out.motion.rotations[k] = unit_quaternion(r.data() + 4 * k, k, joints);
  for (int f = 0; f < out.motion.frame_count; ++f) {
    const double* v = t.data() + static_cast<std::ptrdiff_t>(3) * f;
    out.motion.translations[out.motion.index(f, 0)] = glm::dvec3(v[0], v[1], v[2]);
  }
  return out;
}

// A new motion in pm's skeleton from arrays (see the docstring of Motion.with_frames).
PyMotion with_frames(const PyMotion& pm, const py::object& rot, const py::object& aa, const py::object& tr,
                     const py::object& root_pos, const py::object& fps, const py::object& expr, const py::object& bet) {
  const int joints = joints_of(pm);
  if (!rot.is_none() && !aa.is_none()) throw Error("with_frames: give rotations or axis_angle, not both");
  int frames = -1;
  std::optional<Array> r, a, t, rp, e;
  if (!rot.is_none()) r = array_of(rot, {-1, joints, 4}, "rotations");
  if (!aa.is_none()) a = array_of(aa, {-1, joints, 3}, "axis_angle");
  if (!tr.is_none()) t = array_of(tr, {-1, joints, 3}, "translations");
  if (!root_pos.is_none()) rp = array_of(root_pos, {-1, 3}, "root");
  if (!expr.is_none()) e = array_of(expr, {-1, -1}, "expressions");
  for (const std::optional<Array>* x : {&r, &a, &t, &rp, &e}) {
    if (!*x) continue;
    const int n = static_cast<int>((*x)->shape(0));
    if (frames >= 0 && n != frames)
      throw Error("with_frames: the arrays disagree on the frame count (" + std::to_string(frames) + " and " +
                  std::to_string(n) + ")");
    frames = n;
  }
  if (frames < 0) frames = pm.motion.frame_count;
  if (frames < 1) throw Error("with_frames: a motion needs at least one frame");
  PyMotion out;
  out.name = pm.name;
  const double rate = fps.is_none() ? pm.motion.fps : fps_of(fps, "with_frames: fps");
  out.motion = motion_rest(pm.motion.skeleton, rate, frames);
  out.motion.euler_hints.clear();
  const bool keep = frames == pm.motion.frame_count;  // unset channels keep the motion's own
  if (keep) {
    out.motion.rotations = pm.motion.rotations;
    out.motion.translations = pm.motion.translations;
  }
  for (std::size_t k = 0; k < out.motion.rotations.size(); ++k) {
    if (r) {
      out.motion.rotations[k] = unit_quaternion(r->data() + 4 * k, k, joints);
    } else if (a) {
      const double* v = a->data() + 3 * k;
      out.motion.rotations[k] = expmap_to_quat(glm::dvec3(v[0], v[1], v[2]));
    }
    if (t) {
      const double* v = t->data() + 3 * k;
      out.motion.translations[k] = glm::dvec3(v[0], v[1], v[2]);
    }
  }
  if (rp)
    for (int f = 0; f < frames; ++f) {
      const double* v = rp->data() + static_cast<std::ptrdiff_t>(3) * f;
      out.motion.translations[out.motion.index(f, 0)] = glm::dvec3(v[0], v[1], v[2]);
    }
  out.body = pm.body;
  if (e) {
    out.body.expression_dims = static_cast<int>(e->shape(1));
    out.body.expressions = values_of(*e);
  } else if (!keep) {
    out.body.expressions.clear();  // a face of another length cannot follow
    out.body.expression_dims = 0;
  }
  if (!bet.is_none()) out.body.betas = values_of(array_of(bet, {-1}, "betas"));
  return out;
}

}  // namespace

void bind_motion(py::module_& m) {
  py::class_<PyMotion>(m, "Motion", R"(A motion: per frame, every joint's local rotation and translation in a skeleton.

Arrays are float64 copies. Rotations map a vector from the joint's frame to its parent's.
An SMPL-X .npz motion also carries its body: betas (shape) and expressions (the face).)")
      .def(py::init(&motion_from_arrays), py::arg("joint_names"), py::arg("parents"), py::arg("offsets"),
           py::arg("rotations"), py::arg("root"), py::arg("fps"), py::kw_only(), py::arg("name") = py::none(),
           R"(A motion from arrays, as an editor holds one; usable wherever a motion read from a file is.

joint_names: list of J str (unique, no spaces: BVH names them); parents: J ints, -1 for the
root (joint 0), else the index of a joint before it; offsets: (J, 3) rest offsets from the
parent (the root's is its OFFSET); rotations: (frames, J, 4) local rotations as (w, x, y, z)
quaternions, the order Motion.rotations gives, each scaled to length 1 when it is not (one of
length 0 is an error); root: (frames, 3) root positions; fps: 1 to 1000. Every value must be finite. Written
as BVH, the root has position and rotation channels and the other joints rotations, Z X Y,
so reading the file back gives this motion (to the file's six decimals).)")
      .def_property_readonly("fps", [](const PyMotion& p) { return p.motion.fps; })
      .def_property_readonly("frame_count", frames_of)
      .def("__len__", frames_of)
      .def_property_readonly("joint_count", joints_of)
      .def_property_readonly("name", [](const PyMotion& p) { return p.name; })
      .def_property_readonly("joint_names",
                             [](const PyMotion& p) {
                               std::vector<std::string> n;
                               for (const Joint& j : p.motion.skeleton.joints) n.push_back(j.name);
                               return n;
                             })
      .def_property_readonly("parents",
                             [](const PyMotion& p) {
                               std::vector<int> n;
                               for (const Joint& j : p.motion.skeleton.joints) n.push_back(j.parent);
                               return py::array_t<int>(static_cast<py::ssize_t>(n.size()), n.data());
                             })
      .def_property_readonly("offsets",
                             [](const PyMotion& p) {
                               auto out = new_array({joints_of(p), 3});
                               double* d = out.mutable_data();
                               for (const Joint& j : p.motion.skeleton.joints)
                                 for (int c = 0; c < 3; ++c) *d++ = j.offset[c];
                               return out;
                             })
      .def_property_readonly("rotations", rotations, "local rotations, (frames, joints, 4) quaternions (w, x, y, z)")
      .def_property_readonly("axis_angle", axis_angle,
                             "local rotations as axis * angle (radians), (frames, joints, 3): SMPL-X's `poses`")
      .def_property_readonly("translations", translations,
                             "local translations, (frames, joints, 3): position channels where a joint has them, "
                             "else its offset")
      .def_property_readonly("root", root, "the root joint's translation, (frames, 3)")
      .def_property_readonly("positions", positions, "world joint positions, (frames, joints, 3) (forward kinematics)")
      .def_property_readonly("expressions", expressions, "the face, (frames, coefficients), or None")
      .def_property_readonly("betas", betas, "the body shape, (betas,), or None")
      .def_property_readonly("gender", [](const PyMotion& p) { return p.body.gender; })
      .def("with_frames", with_frames, py::arg("rotations") = py::none(), py::arg("axis_angle") = py::none(),
           py::arg("translations") = py::none(), py::arg("root") = py::none(), py::arg("fps") = py::none(),
           py::arg("expressions") = py::none(), py::arg("betas") = py::none(),
           R"(A new motion in this skeleton from arrays: rotations (frames, joints, 4) as (w, x, y, z)
quaternions (normalised) or axis_angle (frames, joints, 3); translations (frames, joints, 3); root
(frames, 3); expressions (frames, n). What is not given keeps this motion's own values when the
frame count is this motion's, else the rest pose.)")
      .def(
          "slice",
          [](const PyMotion& p, int from, int to) {
            if (from < 0 || to < from || to > p.motion.frame_count)
              throw Error("slice: [" + std::to_string(from) + ", " + std::to_string(to) + ") is outside the " +
                          std::to_string(p.motion.frame_count) + " frames");
            PyMotion out;
            out.name = p.name;
            out.motion = motion_slice(p.motion, from, to);
            out.body = p.body;
            if (p.body.has_face()) {
              const auto d = static_cast<std::size_t>(p.body.expression_dims);
              out.body.expressions.assign(p.body.expressions.begin() + static_cast<std::ptrdiff_t>(from * d),
                                          p.body.expressions.begin() + static_cast<std::ptrdiff_t>(to * d));
            }
            return out;
          },
          py::arg("start"), py::arg("stop"), "frames [start, stop)")
      .def(
          "write",
          [](const PyMotion& p, const py::object& path, const std::string& npz_dtype) {
            const std::string file = path_of(path);
            check_output_file({"", file}, kMotionWriteExtensions);  // as `gmg reenact -o m.txt` refuses it
            const auto floats = enum_from_name(kNpzFloatsNames, npz_dtype);
            if (!floats) throw Error("npz_dtype: '" + npz_dtype + "' is not beat2 or float64");
            const py::gil_scoped_release release;
            motion_write(file, p.motion, p.body, *floats);
          },
          py::arg("path"), py::arg("npz_dtype") = "beat2",
          "writes .npz (SMPL-X, with the body) or .bvh by the path's extension, as `gmg` writes them")
      .def("__repr__", [](const PyMotion& p) {
        return "<gmg.Motion " + std::to_string(p.motion.frame_count) + " frames at " + format_number(p.motion.fps) +
               " fps, " + std::to_string(p.motion.joint_count()) + " joints" +
               (p.body.has_face() ? ", with a face" : "") + ">";
      });

  m.def(
      "read_motion",
      [](const py::object& path, const py::object& skeleton) {
        PyMotion out;
        out.name = path_of(path);
        const std::string templ = skeleton.is_none() ? std::string() : path_of(skeleton);
        const py::gil_scoped_release release;
        out.motion = motion_read(out.name, templ, &out.body);
        return out;
      },
      py::arg("path"), py::arg("skeleton") = py::none(),
      "reads a BVH, or an SMPL-X .npz with a BVH skeleton template (and its body), as gmg reads them");
}

}  // namespace gmg::python
