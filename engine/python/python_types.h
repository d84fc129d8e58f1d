// Internal to the Python module `gmg` (engine/python): the objects it hands to Python and the
// conversions between them and the engine's types. The engine's code does the work; this layer
// only moves data between NumPy/Python and the engine's structs, with the GIL released while
// the engine runs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "audio/wav.h"
#include "engine/config/config.h"
#include "engine/core/error.h"
#include "engine/motion/motion.h"
#include "engine/motion/npz.h"
#include "engine/pipeline/pipeline.h"
#include "graph/motion_graph.h"
#include "text/transcript.h"

namespace gmg::python {

namespace py = pybind11;

// gmg.Motion: a motion (local rotations and translations per frame, in a skeleton) and, for an
// SMPL-X .npz, its body (shape, face).
struct PyMotion {
  Motion motion;
  SmplxBody body;
  std::string name;  // the file it came from, or a label: names it in errors and reports
};

// gmg.Graph: a built or loaded graph, read-only and shared (reenactments from several threads
// may use it at once).
struct PyGraph {
  std::shared_ptr<const MotionGraph> graph;
  std::string name;  // what reports call it: the file it was loaded from, or its first clip
};

// gmg.Reenactment: a reenacted motion with its body and report.
struct PyReenactment {
  PyMotion motion;
  nlohmann::ordered_json report;
};

// A text path from a str or an os.PathLike (os.fspath); gmg::Error for a path with a NUL byte
// (the operating system would read the name only up to it: another file).
std::string path_of(const py::handle& object);
bool is_path(const py::handle& object);

// The arguments as the command line's options take them, each a gmg::Error naming the argument
// (`what`) rather than pybind11's "Unable to cast": a str; a whole number from lo to hi (an int or
// anything with __index__, as NumPy's integers); a sample rate in Hz (a whole number, also as a
// float, within engine/core/limits.h).
std::string text_of(const py::handle& object, const std::string& what);
std::uint64_t whole_of(const py::handle& object, const std::string& what, std::uint64_t lo, std::uint64_t hi);
int sample_rate_of(const py::handle& object, const std::string& what);
// Refuses a NumPy array of complex numbers (NumPy would drop the imaginary part), or of anything
// but numbers, naming `what`; other objects pass (NumPy converts them or says why not).
void check_real_numbers(const py::handle& object, const std::string& what);

// The engine's Config from the Python arguments, as ConfigOptions::make does from the command
// line: the defaults, then `config` (a JSON file's path, or a dict as the file would hold), then
// `set` (a dict of key: value, or a list of "key=value"), then `seed`; validated.
Config config_of(const py::object& config, const py::object& set, const py::object& seed);

// Audio samples from a 1-D array (mono) or a 2-D (samples, channels) array of real numbers (any
// layout: a strided or broadcast view is copied), mixed to mono as the readers mix (the channels'
// mean); checked with check_audio_samples. Complex samples, and a (channels, samples) array (2-D
// with more columns than rows), are refused with what to pass instead.
audio::Audio audio_of(const py::handle& samples, const py::handle& sample_rate, const std::string& name);

// The check gmg evaluate makes of a speech file (audio/speech_check.h speech_level_problem),
// for samples: gmg::Error "name: is silent: ..." unless allow_silence.
void check_speech_level(const audio::Audio& sound, const std::string& name, bool allow_silence);

// Words from a list of (start, end, text) tuples: numbers and a str, else gmg::Error naming the
// word.
std::vector<text::Word> words_of(const py::handle& words);

// A JSON value as the Python object json.loads would give.
py::object to_python(const nlohmann::ordered_json& j);
// A Python object (dict, list, numbers, strings) as JSON, through json.dumps.
nlohmann::json from_python(const py::handle& object, const std::string& name);

void bind_motion(py::module_& m);
void bind_engine(py::module_& m);

// What makes an object of each class, for the refusal of one that was never built.
template <typename T>
const char* made_by();
template <>
inline const char* made_by<PyMotion>() {
  return "gmg.Motion: this object was never built (gmg.Motion(...), gmg.read_motion or Motion.with_frames make one)";
}
template <>
inline const char* made_by<PyGraph>() {
  return "gmg.Graph: this object was never built (gmg.load or gmg.build make one)";
}
template <>
inline const char* made_by<PyReenactment>() {
  return "gmg.Reenactment: this object was never built (gmg.reenact makes one)";
}

}  // namespace gmg::python

// An object made by Class.__new__(Class) without being built has no C++ object, and pybind11
// would hand its methods uninitialised memory (a crash, or garbage): every method, property and
// function that takes one refuses it with gmg.Error instead. These casters replace pybind11's
// own for the three classes in every file of the module (each includes this header).
namespace pybind11::detail {

template <typename T>
struct built_object_caster : type_caster_base<T> {
  bool load(handle src, bool convert) {
    if (!type_caster_base<T>::load(src, convert)) return false;
    const type_info* info = get_type_info(typeid(T));
    if (!src || src.is_none() || info == nullptr || !PyObject_TypeCheck(src.ptr(), info->type)) return true;
    const value_and_holder v_h = reinterpret_cast<instance*>(src.ptr())->get_value_and_holder(info, false);
    if (v_h && !v_h.holder_constructed()) throw gmg::Error(gmg::python::made_by<T>());
    return true;
  }
};

template <>
struct type_caster<gmg::python::PyMotion> : built_object_caster<gmg::python::PyMotion> {};
template <>
struct type_caster<gmg::python::PyGraph> : built_object_caster<gmg::python::PyGraph> {};
template <>
struct type_caster<gmg::python::PyReenactment> : built_object_caster<gmg::python::PyReenactment> {};

}  // namespace pybind11::detail
