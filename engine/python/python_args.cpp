// The Python module's arguments as the engine takes them: paths, text, numbers, samples, words,
// parameters, JSON. Each refuses what the command line would refuse with a gmg::Error naming the
// argument, never pybind11's "Unable to cast Python instance".
#include <charconv>
#include <cmath>

#include "audio/speech_check.h"
#include "audio/speech_energy.h"
#include "engine/core/error.h"
#include "engine/core/json.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"
#include "engine/python/python_types.h"

namespace gmg::python {
namespace {

// "int", "float", "NoneType": how a value's type is named in a message.
std::string type_name(const py::handle& object) { return py::str(py::type::handle_of(object).attr("__name__")); }

// Python's repr of a value, cut to a readable length.
std::string repr_of(const py::handle& object) {
  const std::string r = py::repr(object);
  return r.size() > 60 ? r.substr(0, 60) + "..." : r;
}

// Mixes (samples, channels) to mono as the readers do: the channels' mean.
std::vector<float> mono_of(const float* p, py::ssize_t n, py::ssize_t channels) {
  std::vector<float> out(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    double sum = 0;
    for (py::ssize_t c = 0; c < channels; ++c) sum += p[i * channels + c];
    out[static_cast<std::size_t>(i)] = static_cast<float>(sum / static_cast<double>(channels));
  }
  return out;
}

}  // namespace

bool is_path(const py::handle& object) { return py::isinstance<py::str>(object) || py::hasattr(object, "__fspath__"); }

std::string path_of(const py::handle& object) {
  const py::object p = py::module_::import("os").attr("fspath")(object);
  if (!py::isinstance<py::str>(p)) throw Error("expected a path as text, got bytes");
  const std::string path = p.cast<std::string>();
  if (path.find('\0') != std::string::npos)
    throw Error(escape_nonprintable(path) + ": a path cannot hold a NUL byte (\\x00): the file name would end there");
  return path;
}

std::string text_of(const py::handle& object, const std::string& what) {
  if (!py::isinstance<py::str>(object))
    throw Error(what + ": expected a str, got " + type_name(object) + " " + repr_of(object));
  return object.cast<std::string>();
}

std::uint64_t whole_of(const py::handle& object, const std::string& what, std::uint64_t lo, std::uint64_t hi) {
  // __index__ is what makes a value an integer in Python (int, NumPy's integers), not bool.
  if (py::isinstance<py::bool_>(object) || !PyIndex_Check(object.ptr()))
    throw Error(what + ": expected a whole number, got " + type_name(object) + " " + repr_of(object));
  const std::string text = py::str(py::reinterpret_steal<py::object>(PyNumber_Index(object.ptr())));
  std::uint64_t v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  const bool in_range = r.ec == std::errc() && r.ptr == text.data() + text.size() && v >= lo && v <= hi;
  if (!in_range)
    throw Error(what + ": " + text + " is out of range (" + std::to_string(lo) + " to " + std::to_string(hi) + ")");
  return v;
}

int sample_rate_of(const py::handle& object, const std::string& what) {
  const std::string range = " the " + std::to_string(limits::kMinSampleRate) + " to " +
                            std::to_string(limits::kMaxSampleRate) + " Hz gmg reads";
  if (py::isinstance<py::float_>(object)) {  // 16000.0 is a rate; 16000.5 and nan are not
    const double v = object.cast<double>();
    if (!(std::trunc(v) == v))
      throw Error(what + ": " + format_number(v) + " is not a whole number of Hz (" + range.substr(5) + ")");
    if (v < limits::kMinSampleRate || v > limits::kMaxSampleRate)
      throw Error(what + ": " + format_number(v) + " Hz is outside" + range);
    return static_cast<int>(v);
  }
  if (py::isinstance<py::bool_>(object) || !PyIndex_Check(object.ptr()))
    throw Error(what + ": expected a whole number of Hz, got " + type_name(object) + " " + repr_of(object));
  const std::string text = py::str(py::reinterpret_steal<py::object>(PyNumber_Index(object.ptr())));
  int v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || v < limits::kMinSampleRate ||
      v > limits::kMaxSampleRate)
    throw Error(what + ": " + text + " Hz is outside" + range);
  return v;
}

void check_real_numbers(const py::handle& object, const std::string& what) {
  if (!py::isinstance<py::array>(object)) return;  // a list or tuple: NumPy converts it, or says why not
  const char kind = py::reinterpret_borrow<py::array>(object).dtype().kind();
  if (kind == 'c')
    throw Error(what + ": expected real numbers, got complex ones (pass the real part, e.g. x.real, if that is meant)");
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw Error(what + ": expected an array of numbers, got dtype " +
                py::str(py::reinterpret_borrow<py::array>(object).dtype()).cast<std::string>());
}

audio::Audio audio_of(const py::handle& samples, const py::handle& sample_rate, const std::string& name) {
  if (sample_rate.is_none()) throw Error(name + ": audio given as samples needs sample_rate=");
  const int rate = sample_rate_of(sample_rate, "sample_rate");
  check_real_numbers(samples, name);
  // forcecast with c_style copies any layout (a strided slice, a broadcast view) into a plain array.
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(samples);
  if (!a || a.ndim() < 1 || a.ndim() > 2)
    throw Error(name + ": expected audio samples as a 1-D array (mono) or 2-D (samples, channels)");
  const py::ssize_t n = a.shape(0), channels = a.ndim() == 2 ? a.shape(1) : 1;
  if (channels < 1) throw Error(name + ": the audio has no channels");
  if (a.ndim() == 2 && channels > n)
    throw Error(name + ": a (" + std::to_string(n) + ", " + std::to_string(channels) +
                ") array looks like (channels, samples); pass (samples, channels), e.g. x.T, or mono samples");
  audio::Audio out;
  out.sample_rate = rate;
  out.samples = mono_of(a.data(), n, channels);
  check_audio_samples(out, name);
  return out;
}

void check_speech_level(const audio::Audio& sound, const std::string& name, bool allow_silence) {
  if (allow_silence) return;
  const std::string problem = audio::speech_level_problem(sound.duration(), audio::energy_track(sound));
  if (!problem.empty()) throw Error(audio::speech_refusal(name, problem, {}));
}

std::vector<text::Word> words_of(const py::handle& words) {
  if (py::isinstance<py::str>(words) || !py::isinstance<py::iterable>(words))
    throw Error("words: expected a list of (start_seconds, end_seconds, text), got " + type_name(words));
  std::vector<text::Word> out;
  for (const py::handle& item : words) {
    const std::string which = "words: word " + std::to_string(out.size() + 1);
    if (py::isinstance<py::str>(item) || !py::isinstance<py::sequence>(item) ||
        py::reinterpret_borrow<py::sequence>(item).size() != 3)
      throw Error(which + ": expected (start_seconds, end_seconds, text), got " + repr_of(item));
    const py::sequence t = py::reinterpret_borrow<py::sequence>(item);
    double times[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      const py::object v = t[static_cast<py::size_t>(k)];
      const auto refuse = [&] {
        return Error(which + ": its " + (k == 0 ? "start" : "end") + " must be a number of seconds, got " +
                     type_name(v) + " " + repr_of(v));
      };
      if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v) || py::isinstance<py::bytes>(v)) throw refuse();
      try {
        times[k] = py::float_(v).cast<double>();  // float(v): an int, a float, NumPy's numbers
      } catch (const py::error_already_set&) {
        throw refuse();
      }
    }
    out.push_back({times[0], times[1], text_of(t[2], which + ": its text")});
  }
  return out;
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
        for (const py::handle& item : set) config_set_assignment(c, text_of(item, "set"));
      }
      config_validate(c);
    } catch (const Error& e) {
      const std::string what = e.what();
      throw Error(what.rfind("--set", 0) == 0 ? what : "--set: " + what);
    }
  }
  if (!seed.is_none()) c.seed = whole_of(seed, "seed", 0, UINT64_MAX);
  config_validate(c);
  return c;
}

py::object to_python(const nlohmann::ordered_json& j) {
  return py::module_::import("json").attr("loads")(json_dump(j, -1));
}

nlohmann::json from_python(const py::handle& object, const std::string& name) {
  const std::string text = py::module_::import("json").attr("dumps")(object).cast<std::string>();
  return parse_json_text(text, name);
}

}  // namespace gmg::python
