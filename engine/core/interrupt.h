// Letting a long job stop cleanly on Ctrl-C (batch runs, video encoding), and the one exit-status
// contract of an interrupted command.
//
// Contract (every gmg command): SIGINT (Ctrl-C), SIGTERM and SIGHUP remove the temporary files of
// the outputs being written, and the process then ends as the signal would, with its default
// action: a shell sees status 128 + N, 130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP, and a
// parent that waits sees "killed by signal N" (so a shell loop around gmg stops on Ctrl-C as it
// would around any tool). Most commands die at once (InterruptCleanup); `batch` and `render`
// first finish or stop their step (InterruptFlag, then Interrupted).
#pragma once

#include <atomic>
#include <csignal>
#include <string>

#include "engine/core/error.h"

namespace gmg {

// The signals an interrupted command cleans up after.
inline constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

// A process-wide table of temporary files that a SIGINT, SIGTERM or SIGHUP removes (see
// InterruptCleanup). register_temporary_file returns its slot, or -1 when the table (256 paths
// of up to 4095 bytes) is full and the file will not be removed on a signal.
int register_temporary_file(const std::string& path) noexcept;
void unregister_temporary_file(int slot) noexcept;
// Unlinks every registered file. Async-signal-safe (unlink(2) on a fixed array): for handlers.
void remove_registered_temporary_files() noexcept;
// Removes them and ends the process as `sig` would, its handler reset to the default.
// Async-signal-safe: for handlers.
void remove_temporaries_and_die(int sig) noexcept;

// While alive, SIGINT, SIGTERM and SIGHUP remove the registered temporary files and then end the
// process as the signal would (the previous handlers are restored on destruction; the exit
// contract is in engine/core/interrupt.h). With a program name, the handler first writes
// "<program>: interrupted by SIGINT; no output written" on standard error. cli_main holds one
// for every subcommand; `gmg batch` and `gmg render` install a graceful handler on top
// (InterruptFlag), which removes the temporary files before dying on a second signal.
class InterruptCleanup {
 public:
  explicit InterruptCleanup(const char* program = nullptr);
  ~InterruptCleanup();
  InterruptCleanup(const InterruptCleanup&) = delete;
  InterruptCleanup& operator=(const InterruptCleanup&) = delete;

 private:
  struct Saved;
  Saved* saved_;
};
// While alive, the first SIGINT, SIGTERM or SIGHUP only raises flag(): the job notices it between
// steps, stops, removes its partial outputs and reports. A second one does not wait: it removes
// the registered temporary files and ends the process as the signal would.
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
