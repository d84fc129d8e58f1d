#include "engine/core/interrupt.h"

#include <signal.h>

#include "engine/core/files.h"

namespace gmg {
namespace {

std::atomic<bool> g_raised{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the handler sets it");

extern "C" void on_interrupt(int sig) {
  if (g_raised.load()) {  // second signal: die the ordinary way, leaving no temporary file
    remove_temporaries_and_die(sig);
    return;
  }
  g_raised.store(true);
}

}  // namespace

InterruptFlag::InterruptFlag() {
  g_raised.store(false);
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  ::sigaction(SIGINT, &sa, &old_int_);
  ::sigaction(SIGTERM, &sa, &old_term_);
}

InterruptFlag::~InterruptFlag() {
  ::sigaction(SIGINT, &old_int_, nullptr);
  ::sigaction(SIGTERM, &old_term_, nullptr);
}

const std::atomic<bool>& InterruptFlag::flag() { return g_raised; }

}  // namespace gmg
