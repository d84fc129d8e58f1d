// The Python module `gmg`: the engine over NumPy arrays and files (see the README's "From
// Python"). gmg::Error becomes gmg.Error with the same message, gmg::Interrupted KeyboardInterrupt.
#include "engine/core/error.h"
#include "engine/core/interrupt.h"
#include "engine/python/python_types.h"

#ifndef GMG_VERSION
#define GMG_VERSION "unknown"
#endif

PYBIND11_MODULE(gmg, m) {
  namespace py = pybind11;
  m.doc() = "gmg: gesture motion graphs - reenact a speaker's gestures for new speech";
  m.attr("__version__") = GMG_VERSION;
  // gmg::Error as gmg.Error with the same message. A message may quote bytes of a file that are
  // not UTF-8 (a binary file read as text): they become U+FFFD rather than a UnicodeDecodeError.
  // Never destroyed: a Python object must not be released after the interpreter has finalised.
  static const auto* const error = new py::exception<gmg::Error>(m, "Error");
  // pybind11's translator type takes the pointer by value.
  py::register_exception_translator([](std::exception_ptr p) {  // NOLINT(performance-unnecessary-value-param)
    try {
      if (p) std::rethrow_exception(p);
    } catch (const gmg::Interrupted& e) {  // a job stopped by a signal (engine/core/interrupt.h)
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const gmg::Error& e) {
      // The speech checks' hint names the command line's flag; from Python it is the argument.
      std::string what = e.what();
      const std::string flag = "--allow-silence", argument = "allow_silence=True";
      if (const std::size_t at = what.find(flag); at != std::string::npos) what.replace(at, flag.size(), argument);
      PyObject* text = PyUnicode_DecodeUTF8(what.data(), static_cast<Py_ssize_t>(what.size()), "replace");
      PyErr_SetObject(error->ptr(), text);
      Py_XDECREF(text);
    }
  });
  gmg::python::bind_motion(m);
  gmg::python::bind_engine(m);
}
