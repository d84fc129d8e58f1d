// Letting a long job stop cleanly on Ctrl-C (batch runs, video encoding).
#pragma once

#include <atomic>
#include <csignal>

namespace gmg {

// While alive, the first SIGINT or SIGTERM only raises flag(): the job notices it between
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

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace gmg
