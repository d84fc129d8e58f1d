// The app tests' way to run `gmg ...` in-process: cli_main with its stdout and stderr captured.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/cli/cli.h"

namespace gmg::testing {

struct CliRun {
  int code = -1;    // cli_main's exit code
  std::string out;  // what it printed on stdout
  std::string err;  // and on stderr
};

// Runs `gmg args...` (args without the program name).
inline CliRun run_gmg(std::vector<std::string> args) {
  args.insert(args.begin(), "gmg");
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  CliRun r;
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  r.code = cli_main(static_cast<int>(args.size()), argv.data());
  r.out = ::testing::internal::GetCapturedStdout();
  r.err = ::testing::internal::GetCapturedStderr();
  return r;
}

}  // namespace gmg::testing
