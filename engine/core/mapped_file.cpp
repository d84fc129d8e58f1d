#include "engine/core/mapped_file.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <mutex>

#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "engine/core/error.h"
#include "engine/core/file_read.h"

namespace gmg {

namespace {

// The mappings a SIGBUS may hit, read by the signal handler without a lock: a slot is taken by
// storing its end before its begin, and freed by clearing its begin first.
struct MappingSlot {
  std::atomic<std::uintptr_t> begin{0};
  std::atomic<std::uintptr_t> end{0};
  std::atomic<int> faulted{0};
};
constexpr int kMappingSlots = 256;
MappingSlot g_mappings[kMappingSlots];
struct sigaction g_previous_sigbus {};
std::atomic<bool> g_sigbus_installed{false};

void on_sigbus(int sig, siginfo_t* info, void* context) {
  const auto addr = reinterpret_cast<std::uintptr_t>(info->si_addr);
  for (MappingSlot& m : g_mappings) {
    const std::uintptr_t begin = m.begin.load(std::memory_order_acquire);
    if (begin == 0 || addr < begin || addr >= m.end.load(std::memory_order_acquire)) continue;
    // The file ends before this page now: zero pages in place of the rest of the mapping, so the
    // faulting read (retried on return) and all later ones read zeros. mmap is a plain system
    // call here; it touches no lock of the C library.
    const std::uintptr_t page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    const std::uintptr_t from = addr / page * page;
    const std::uintptr_t end = m.end.load(std::memory_order_acquire);
    void* const at = reinterpret_cast<void*>(from);  // NOLINT(performance-no-int-to-ptr): the faulting page
    void* p = ::mmap(at, end - from, PROT_READ, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0);
    if (p == MAP_FAILED) break;
    m.faulted.store(1, std::memory_order_release);
    return;
  }
  // Not ours: what would have happened without this handler.
  if (g_previous_sigbus.sa_flags & SA_SIGINFO) {
    if (g_previous_sigbus.sa_sigaction) return g_previous_sigbus.sa_sigaction(sig, info, context);
  } else if (g_previous_sigbus.sa_handler != SIG_DFL && g_previous_sigbus.sa_handler != SIG_IGN) {
    return g_previous_sigbus.sa_handler(sig);
  }
  ::signal(SIGBUS, SIG_DFL);  // returning re-runs the read, which now ends the process
}

void install_sigbus_handler() {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (g_sigbus_installed.load()) return;
  struct sigaction sa {};
  sa.sa_sigaction = on_sigbus;
  sa.sa_flags = SA_SIGINFO;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGBUS, &sa, &g_previous_sigbus);
  g_sigbus_installed.store(true);
}

int take_mapping_slot(const void* data, std::size_t size) {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  for (int i = 0; i < kMappingSlots; ++i) {
    MappingSlot& m = g_mappings[i];
    if (m.begin.load() != 0 || m.end.load() != 0) continue;
    m.faulted.store(0);
    m.end.store(reinterpret_cast<std::uintptr_t>(data) + size, std::memory_order_release);
    m.begin.store(reinterpret_cast<std::uintptr_t>(data), std::memory_order_release);
    return i;
  }
  return -1;
}

long long mtime_ns(const struct stat& st) {
  return static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
}

}  // namespace

MappedFile::MappedFile(const std::string& path) : path_(path) {
  FileDescriptor fd = open_regular(path, &size_);
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  mtime_ns_ = mtime_ns(st);
  if (size_ == 0) return;
  install_sigbus_handler();
  void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd.get(), 0);
  if (p == MAP_FAILED) throw Error(path + ": cannot read (" + std::strerror(errno) + ")");
  data_ = static_cast<const char*>(p);
  slot_ = take_mapping_slot(data_, size_);
  if (slot_ < 0) {
    ::munmap(p, size_);
    throw Error(path + ": cannot read (too many files mapped at once)");
  }
  fd_ = fd.release();
}

MappedFile::~MappedFile() {
  if (slot_ >= 0) {
    MappingSlot& m = g_mappings[slot_];
    m.begin.store(0, std::memory_order_release);
    m.end.store(0, std::memory_order_release);
  }
  if (data_) ::munmap(const_cast<char*>(data_), size_);
  if (fd_ >= 0) ::close(fd_);
}

void release_mapped_pages(const void* p, std::size_t size) {
  if (!p || size == 0) return;
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t end = begin + size;
  const std::uintptr_t page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  for (const MappingSlot& m : g_mappings) {
    const std::uintptr_t mb = m.begin.load(std::memory_order_acquire);
    if (mb == 0) continue;
    const std::uintptr_t me = m.end.load(std::memory_order_acquire);
    const std::uintptr_t from = (std::max(begin, mb) + page - 1) / page * page;
    const std::uintptr_t to = std::min(end, me) / page * page;
    // NOLINTNEXTLINE(performance-no-int-to-ptr): pages of a mapping this process made
    if (to > from) ::madvise(reinterpret_cast<void*>(from), to - from, MADV_DONTNEED);
  }
}

bool MappedFile::changed() const {
  if (slot_ >= 0 && g_mappings[slot_].faulted.load(std::memory_order_acquire) != 0) return true;
  if (fd_ < 0) return false;
  struct stat st {};
  if (::fstat(fd_, &st) != 0) return true;
  return static_cast<std::size_t>(st.st_size) != size_ || mtime_ns(st) != mtime_ns_;
}

void MappedFile::check_unchanged() const {
  if (!changed()) return;
  throw Error(path_ + ": changed while in use (it was truncated or written to; read it again when it is complete)");
}

void advise_huge_pages(const void* p, std::size_t size) {
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t from = (begin + kHuge - 1) / kHuge * kHuge, to = (begin + size) / kHuge * kHuge;
  // NOLINTNEXTLINE(performance-no-int-to-ptr): pages of this process's own allocation
  if (p && to > from) ::madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE);
#else
  (void)p;
  (void)size;
#endif
}

void MappedFile::release(std::size_t offset, std::size_t size) const {
  if (!data_ || offset >= size_) return;
  const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  const std::size_t from = (offset + page - 1) / page * page;
  const std::size_t to = std::min(size_, offset + size) / page * page;
  if (to > from) ::madvise(const_cast<char*>(data_) + from, to - from, MADV_DONTNEED);
}

}  // namespace gmg
