// The one error type every reader and job throws.
//
// Contract: the message is complete and user-facing: it names the file (when
// there is one), the place in it (line or byte offset) and the problem, e.g.
// "take.bvh: line 12: expected 6 channels, found 3". The command-line tool
// prints it as is and exits non-zero, so callers never add context twice.
#pragma once

#include <new>
#include <sstream>
#include <stdexcept>
#include <string>

namespace gmg {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Builds "path: line N: what" (line omitted when 0).
inline std::string error_at_line(const std::string& path, long line, const std::string& what) {
  std::ostringstream os;
  os << path;
  if (line > 0) os << ": line " << line;
  os << ": " << what;
  return os.str();
}

// Builds "path: byte N: what".
inline std::string error_at_byte(const std::string& path, long long offset, const std::string& what) {
  std::ostringstream os;
  os << path << ": byte " << offset << ": " << what;
  return os.str();
}

// Runs f and returns what it returns; an allocation failure inside (std::bad_alloc, or
// std::length_error for a size no container can hold) becomes gmg::Error "<what>: out of memory
// <doing>", so even that error names the file it came from.
template <typename F>
auto naming_memory_errors(const std::string& what, const std::string& doing, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::bad_alloc&) {
    throw Error(what + ": out of memory " + doing);
  } catch (const std::length_error&) {
    throw Error(what + ": out of memory " + doing + " (a size beyond what can be allocated)");
  }
}

// Parameter checks of every stage: throws gmg::Error "invalid config: <what>" when !ok. `what`
// names the key and the rule ("l_pn must be >= 1").
inline void require_param(bool ok, const std::string& what) {
  if (!ok) throw Error("invalid config: " + what);
}

}  // namespace gmg
