// Shared by the libFuzzer harnesses of tests/fuzz: each feeds the bytes to one reader and accepts
// exactly one outcome besides success, a gmg::Error (whose message must name the input). Any
// other exception escapes and libFuzzer reports it as a crash, as it does for a sanitizer
// finding, a timeout (-timeout) or too much memory (-rss_limit_mb / -malloc_limit_mb).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "engine/core/error.h"

namespace gmg::fuzz {

inline std::string bytes_of(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Runs f; a gmg::Error is an accepted outcome but must name `name` (the input's label).
template <typename F>
void expect_success_or_error(const std::string& name, F&& f) {
  try {
    f();
  } catch (const gmg::Error& e) {
    const std::string what = e.what();
    if (what.find(name) == std::string::npos && what.rfind("invalid config: ", 0) != 0 &&
        what.rfind("config key ", 0) != 0 && what.rfind("unknown config key ", 0) != 0)
      std::abort();  // an error that does not say which input it is about
  }
}

}  // namespace gmg::fuzz
