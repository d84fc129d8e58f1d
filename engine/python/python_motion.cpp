// gmg.Motion and the conversions between Python objects and the engine's types.
#include <cmath>
#include <optional>

#include <pybind11/stl.h>

#include "engine/core/error.h"
#include "engine/core/json.h"
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
  const double rate = fps.is_none() ? pm.motion.fps : fps.cast<double>();
  if (!(rate > 0 && rate <= 1000)) throw Error("with_frames: fps must be in (0, 1000]");
  out.motion = motion_rest(pm.motion.skeleton, rate, frames);
  out.motion.euler_hints.clear();
  const bool keep = frames == pm.motion.frame_count;  // unset channels keep the motion's own
  if (keep) {
    out.motion.rotations = pm.motion.rotations;
    out.motion.translations = pm.motion.translations;
  }
  for (std::size_t k = 0; k < out.motion.rotations.size(); ++k) {
    if (r) {
      const double* q = r->data() + 4 * k;
      const glm::dquat v(q[0], q[1], q[2], q[3]);
      const double norm = std::sqrt(glm::dot(v, v));
      if (!(norm > 1e-9)) throw Error("rotations: quaternion " + std::to_string(k) + " has length 0");
      out.motion.rotations[k] = v / norm;
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

bool is_path(const py::handle& object) { return py::isinstance<py::str>(object) || py::hasattr(object, "__fspath__"); }

std::string path_of(const py::handle& object) {
  const py::object p = py::module_::import("os").attr("fspath")(object);
  if (!py::isinstance<py::str>(p)) throw Error("expected a path as text, got bytes");
  return p.cast<std::string>();
}

Config config_of(const py::object& config, const py::object& set, const py::object& seed) {
  Config c;
  if (!config.is_none()) {
    if (is_path(config)) {
      config_load_file(c, path_of(config));
      try {
        config_validate(c);  // before the assignments, as the command line's --config
      } catch (const Error& e) {
        throw Error(path_of(config) + ": " + e.what());
      }
    } else {
      config_load_text(c, json_dump(from_python(config, "config")), "config");
    }
  }
  if (!set.is_none()) {
    // As the command line's --set: a bad key or value, or a rule the assignments break, is
    // "--set: ..." (cli_common.cpp ConfigOptions::make).
    try {
      if (py::isinstance<py::dict>(set)) {
        for (const auto& [key, value] : set.cast<py::dict>()) {
          std::string text;
          if (py::isinstance<py::bool_>(value))
            text = value.cast<bool>() ? "true" : "false";
          else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value))
            for (const py::handle& item : value) text += (text.empty() ? "" : ",") + py::str(item).cast<std::string>();
          else
            text = py::str(value).cast<std::string>();
          config_set(c, py::str(key).cast<std::string>(), text);
        }
      } else {
        for (const py::handle& item : set) config_set_assignment(c, item.cast<std::string>());
      }
      config_validate(c);
    } catch (const Error& e) {
      const std::string what = e.what();
      throw Error(what.rfind("--set", 0) == 0 ? what : "--set: " + what);
    }
  }
  if (!seed.is_none()) c.seed = seed.cast<std::uint64_t>();
  config_validate(c);
  return c;
}

audio::Audio audio_of(const py::handle& samples, const py::handle& sample_rate, const std::string& name) {
  if (sample_rate.is_none()) throw Error(name + ": audio given as samples needs sample_rate=");
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(samples);
  if (!a || a.ndim() < 1 || a.ndim() > 2)
    throw Error(name + ": expected audio samples as a 1-D array (mono) or 2-D (samples, channels)");
  audio::Audio out;
  out.sample_rate = sample_rate.cast<int>();
  const py::ssize_t n = a.shape(0), channels = a.ndim() == 2 ? a.shape(1) : 1;
  if (channels < 1) throw Error(name + ": the audio has no channels");
  out.samples.resize(static_cast<std::size_t>(n));
  const float* p = a.data();
  for (py::ssize_t i = 0; i < n; ++i) {
    double sum = 0;
    for (py::ssize_t c = 0; c < channels; ++c) sum += p[i * channels + c];
    out.samples[static_cast<std::size_t>(i)] = static_cast<float>(sum / static_cast<double>(channels));
  }
  check_audio_samples(out, name);
  return out;
}

std::vector<text::Word> words_of(const py::handle& words) {
  std::vector<text::Word> out;
  for (const py::handle& item : words) {
    const py::sequence t = py::reinterpret_borrow<py::sequence>(item);
    if (t.size() != 3) throw Error("words: each word is (start_seconds, end_seconds, text)");
    out.push_back({t[0].cast<double>(), t[1].cast<double>(), t[2].cast<std::string>()});
  }
  return out;
}

py::object to_python(const nlohmann::ordered_json& j) {
  return py::module_::import("json").attr("loads")(json_dump(j, -1));
}

nlohmann::json from_python(const py::handle& object, const std::string& name) {
  const std::string text = py::module_::import("json").attr("dumps")(object).cast<std::string>();
  return parse_json_text(text, name);
}

void bind_motion(py::module_& m) {
  py::class_<PyMotion>(m, "Motion", R"(A motion: per frame, every joint's local rotation and translation in a skeleton.

Arrays are float64 copies. Rotations map a vector from the joint's frame to its parent's.
An SMPL-X .npz motion also carries its body: betas (shape) and expressions (the face).)")
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
            const auto floats = enum_from_name(kNpzFloatsNames, npz_dtype);
            if (!floats) throw Error("npz_dtype: '" + npz_dtype + "' is not beat2 or float64");
            const py::gil_scoped_release release;
            motion_write(file, p.motion, p.body, *floats);
          },
          py::arg("path"), py::arg("npz_dtype") = "beat2",
          "writes .npz (SMPL-X, with the body) when the path ends in .npz, else BVH, as `gmg` writes them")
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
