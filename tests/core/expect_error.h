// Test helper for error messages: every file error must name the file, so tests look inside the
// message rather than only at the exception type. (Used by the core, motion, audio and text
// tests; a candidate for tests/test_support.h.)
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

}  // namespace gmg::testing

#define EXPECT_CONTAINS(haystack, needle)                          \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) \
      << "message: \"" << (haystack) << "\" should contain \"" << (needle) << "\""
