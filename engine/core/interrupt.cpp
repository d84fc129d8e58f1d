#include "engine/core/interrupt.h"

#include <signal.h>

#include "engine/core/files.h"

namespace gmg {
namespace {

std::atomic<bool> g_raised{false};
std::atomic<int> g_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free, "the handler sets it");
static_assert(std::atomic<int>::is_always_lock_free, "the handler sets it");

extern "C" void on_interrupt(int sig) {
  if (g_raised.load()) {  // second signal: die the ordinary way, leaving no temporary file
    remove_temporaries_and_die(sig);
    return;
  }
  g_signal.store(sig);
  g_raised.store(true);
}

}  // namespace

InterruptFlag::InterruptFlag() {
  g_raised.store(false);
  g_signal.store(0);
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  ::sigaction(SIGINT, &sa, &old_int_);
  ::sigaction(SIGTERM, &sa, &old_term_);
  ::sigaction(SIGHUP, &sa, &old_hup_);
}

InterruptFlag::~InterruptFlag() {
  ::sigaction(SIGINT, &old_int_, nullptr);
  ::sigaction(SIGTERM, &old_term_, nullptr);
  ::sigaction(SIGHUP, &old_hup_, nullptr);
}

const std::atomic<bool>& InterruptFlag::flag() { return g_raised; }

int InterruptFlag::signal_number() { return g_signal.load(); }

std::string signal_name(int sig) {
  switch (sig) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "signal " + std::to_string(sig);
  }
}

void throw_if_interrupted(const std::string& what, const std::string& consequence) {
  if (!InterruptFlag::raised()) return;
  const int sig = InterruptFlag::signal_number() != 0 ? InterruptFlag::signal_number() : SIGINT;
  throw Interrupted(sig, what + ": interrupted by " + signal_name(sig) + "; " + consequence);
}

}  // namespace gmg
