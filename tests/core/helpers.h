// Test helpers used by the core, motion, audio and text tests (candidates for
// tests/test_support.h): error messages, one-spot text edits.
//
// Every file error must name the file, so tests look inside the message rather than only at the
// exception type.
#pragma once

#include <exception>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace gmg::testing {

// Runs f and returns the message of the gmg::Error it throws; records a test failure (and
// returns "" or the other exception's message) when it throws nothing or something else.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const gmg::Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected gmg::Error, got another exception: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << "expected gmg::Error, nothing was thrown";
  return "";
}

// s with the first occurrence of `from` replaced by `to`; a test failure when `from` is absent
// (a bug in the test, not in the code under test).
inline std::string replace_once(std::string s, const std::string& from, const std::string& to) {
  const std::size_t p = s.find(from);
  EXPECT_NE(p, std::string::npos) << "test bug: " << from << " not in the text";
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

}  // namespace gmg::testing

#define EXPECT_CONTAINS(haystack, needle)                          \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) \
      << "message: \"" << (haystack) << "\" should contain \"" << (needle) << "\""
