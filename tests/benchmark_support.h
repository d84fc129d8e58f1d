// Helpers shared by the benchmarks (tests/bench_*.cpp): timing a whole command as a child process,
// this process's own CPU time and peak memory, and the spread of repeated figures. The benchmarks
// print figures and assert nothing about time (machines are shared and noisy).
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace gmg::bench {

// One run of a child command: wall and CPU seconds (user + system, from wait4), peak resident
// memory.
struct CommandRun {
  double wall = 0, cpu = 0, rss_mb = 0;
};

// Runs args (args[0] is the program's path) with stdout to `out` and stderr to /dev/null; a
// command that fails ends the benchmark with a message naming it.
CommandRun run_command(const std::vector<std::string>& args, const std::string& out = "/dev/null");

double process_cpu_seconds();
double thread_cpu_seconds();
double peak_rss_mb();  // this process's, so far

// Wall and process CPU seconds since construction.
struct Timer {
  std::chrono::steady_clock::time_point wall0 = std::chrono::steady_clock::now();
  double cpu0 = process_cpu_seconds();
  double wall() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count(); }
  double cpu() const { return process_cpu_seconds() - cpu0; }
};

struct Spread {
  double min, median, max;
};
Spread spread(std::vector<double> values);  // of a non-empty list
double median(std::vector<double> values);

}  // namespace gmg::bench
