// Letting a long job stop cleanly on Ctrl-C (batch runs, video encoding), and the one exit-status
// contract of an interrupted command.
//
// Contract (every gmg command): SIGINT (Ctrl-C), SIGTERM and SIGHUP remove the temporary files of
// the outputs being written, and the process then ends as the signal would, with its default
// action: a shell sees status 128 + N, 130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP, and a
// parent that waits sees "killed by signal N" (so a shell loop around gmg stops on Ctrl-C as it
// would around any tool). Most commands die at once (InterruptCleanup, engine/core/files.h);
// `batch` and `render` first finish or stop their step (InterruptFlag, then Interrupted).
#pragma once

#include <atomic>
#include <csignal>
#include <string>

#include "engine/core/error.h"

namespace gmg {

// While alive, the first SIGINT, SIGTERM or SIGHUP only raises flag(): the job notices it between
// steps, stops, removes its partial outputs and reports. A second one does not wait: it removes
// the registered temporary files (engine/core/files.h) and ends the process as the signal would.
// The previous handlers are restored on destruction. One at a time.
class InterruptFlag {
 public:
  InterruptFlag();
  ~InterruptFlag();
  InterruptFlag(const InterruptFlag&) = delete;
  InterruptFlag& operator=(const InterruptFlag&) = delete;

  // Raised by a signal since construction (lock-free, so a handler may set it).
  static const std::atomic<bool>& flag();
  static bool raised() { return flag().load(); }
  // The signal that raised it (SIGINT, SIGTERM or SIGHUP); 0 when none came. Kept after the
  // flag's destruction, until the next InterruptFlag.
  static int signal_number();

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
  struct sigaction old_hup_ {};
};

// "SIGINT", "SIGTERM", "SIGHUP", else "signal N".
std::string signal_name(int sig);

// A job that stopped because of a signal: its partial outputs are removed; the command-line tool
// prints the message and ends as the signal would (the contract above). The Python module turns
// it into KeyboardInterrupt.
class Interrupted : public Error {
 public:
  Interrupted(int sig, const std::string& message) : Error(message), signal_(sig) {}
  int signal_number() const { return signal_; }

 private:
  int signal_;
};

// Throws Interrupted "<what>: interrupted by SIGINT; <consequence>" when InterruptFlag::raised().
void throw_if_interrupted(const std::string& what, const std::string& consequence);

}  // namespace gmg
