// Internal to the Python module `gmg` (engine/python): the objects it hands to Python and the
// conversions between them and the engine's types. The engine's code does the work; this layer
// only moves data between NumPy/Python and the engine's structs, with the GIL released while
// the engine runs.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "audio/wav.h"
#include "engine/config/config.h"
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

// A text path from a str or an os.PathLike (os.fspath).
std::string path_of(const py::handle& object);
bool is_path(const py::handle& object);

// The engine's Config from the Python arguments, as ConfigOptions::make does from the command
// line: the defaults, then `config` (a JSON file's path, or a dict as the file would hold), then
// `set` (a dict of key: value, or a list of "key=value"), then `seed`; validated.
Config config_of(const py::object& config, const py::object& set, const py::object& seed);

// Audio samples from a 1-D array (mono) or a 2-D (samples, channels) array, mixed to mono as the
// readers mix (the channels' mean); checked with check_audio_samples.
audio::Audio audio_of(const py::handle& samples, const py::handle& sample_rate, const std::string& name);

// Words from a list of (start, end, text) tuples.
std::vector<text::Word> words_of(const py::handle& words);

// A JSON value as the Python object json.loads would give.
py::object to_python(const nlohmann::ordered_json& j);
// A Python object (dict, list, numbers, strings) as JSON, through json.dumps.
nlohmann::json from_python(const py::handle& object, const std::string& name);

void bind_motion(py::module_& m);
void bind_engine(py::module_& m);

}  // namespace gmg::python
