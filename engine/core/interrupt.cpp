#include "engine/core/interrupt.h"

#include <atomic>
#include <cstring>
#include <iterator>
#include <type_traits>

#include <signal.h>
#include <unistd.h>

namespace gmg {

// ---- Temporary files removed on a signal, InterruptCleanup ----------------------------------------

namespace {

constexpr int kSlots = 256;
constexpr std::size_t kPathBytes = 4096;

// state: 0 free, 1 being filled (skipped by the handler), 2 registered. No member has an
// initialiser: the table is in static storage, zeroed before the program starts, and a slot with
// a non-trivial constructor made start-up run it over all 256 slots, a page fault for each of the
// 1 MiB's pages in every command.
struct TemporarySlot {
  std::atomic<int> state;
  char path[kPathBytes];
};
static_assert(std::is_trivially_default_constructible_v<TemporarySlot>,
              "the slots are zeroed static storage: no constructor to run at start-up");
TemporarySlot g_temporaries[kSlots];

// "<program>: interrupted by " when InterruptCleanup was given a program name; written by the
// handler with write(2), so it is fixed before any signal can come.
char g_interrupt_message[128] = {0};

void write_stderr(const char* text) noexcept {
  const std::size_t n = std::strlen(text);
  if (n > 0 && ::write(2, text, n) < 0) {
    // nothing to do: the process is about to end
  }
}

extern "C" void cleanup_and_die(int sig) {
  if (g_interrupt_message[0] != '\0') {
    write_stderr(g_interrupt_message);
    write_stderr(sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : sig == SIGHUP ? "SIGHUP" : "a signal");
    write_stderr("; no output written\n");
  }
  remove_temporaries_and_die(sig);
}

}  // namespace

void remove_temporaries_and_die(int sig) noexcept {
  remove_registered_temporary_files();
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  ::raise(sig);
}

int register_temporary_file(const std::string& path) noexcept {
  if (path.size() >= kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_temporaries[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_temporaries[i].path, path.c_str(), path.size() + 1);
    g_temporaries[i].state.store(2);
    return i;
  }
  return -1;
}

void unregister_temporary_file(int slot) noexcept {
  if (slot >= 0 && slot < kSlots) g_temporaries[slot].state.store(0);
}

void remove_registered_temporary_files() noexcept {
  for (TemporarySlot& s : g_temporaries)
    if (s.state.load() == 2) ::unlink(s.path);
}

struct InterruptCleanup::Saved {
  struct sigaction old[std::size(kCleanupSignals)];
};

InterruptCleanup::InterruptCleanup(const char* program) : saved_(new Saved) {
  g_interrupt_message[0] = '\0';
  if (program != nullptr && std::strlen(program) + 24 < sizeof g_interrupt_message) {
    std::strcpy(g_interrupt_message, program);
    std::strcat(g_interrupt_message, ": interrupted by ");
  }
  struct sigaction sa {};
  sa.sa_handler = cleanup_and_die;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  for (std::size_t i = 0; i < std::size(kCleanupSignals); ++i) ::sigaction(kCleanupSignals[i], &sa, &saved_->old[i]);
}

InterruptCleanup::~InterruptCleanup() {
  g_interrupt_message[0] = '\0';
  for (std::size_t i = 0; i < std::size(kCleanupSignals); ++i)
    ::sigaction(kCleanupSignals[i], &saved_->old[i], nullptr);
  delete saved_;
}

// ---- InterruptFlag ------------------------------------------------------------------------------

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
