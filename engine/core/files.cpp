#include "engine/core/files.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <type_traits>

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "engine/core/error.h"
#include "engine/core/strings.h"

namespace gmg {
namespace fs = std::filesystem;

// ---- Interruption -------------------------------------------------------------------------------

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

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

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

// ---- Writing ------------------------------------------------------------------------------------

namespace {

thread_local OutputTransaction* t_transaction = nullptr;

void remove_quietly(const std::string& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

}  // namespace

void rename_into_place(const std::string& temp, const std::string& path) {
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    remove_quietly(temp);
    throw Error(path + ": cannot rename the finished file into place (" + ec.message() + ")");
  }
}

void BlockWriter::write(const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    if (buffer_.empty() && size >= block_) {  // a whole block at a block boundary: no copy
      out_.write(p, static_cast<std::streamsize>(block_));
      p += block_;
      size -= block_;
      continue;
    }
    if (buffer_.capacity() < block_) buffer_.reserve(block_);
    const std::size_t n = std::min(size, block_ - buffer_.size());
    buffer_.insert(buffer_.end(), p, p + n);
    p += n;
    size -= n;
    if (buffer_.size() == block_) flush();
  }
}

void BlockWriter::flush() {
  if (!buffer_.empty()) out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool binary) {
  const std::string temp = temporary_name_for(path);
  const int slot = register_temporary_file(temp);  // before the file exists, so a signal never misses it
  auto abandon = [&] {
    remove_quietly(temp);
    unregister_temporary_file(slot);
  };
  {
    std::ofstream out(temp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
    if (!out) {
      const int err = errno;
      unregister_temporary_file(slot);
      throw Error(path + ": cannot write file (" + std::strerror(err) + ")");
    }
    try {
      write(out);
    } catch (...) {
      out.close();
      abandon();
      throw;
    }
    if (out) errno = 0;  // else keep the reason of the write that failed
    out.flush();
    if (!out) {
      const int err = errno;  // the failing write's reason (ENOSPC on a full disk), when it kept it
      out.close();
      abandon();
      throw Error(path + ": cannot write (" + (err != 0 ? std::strerror(err) : "the disk may be full") + ")");
    }
  }
  if (t_transaction) {
    t_transaction->stage(temp, path, slot);
    return;
  }
  try {
    rename_into_place(temp, path);
  } catch (...) {
    unregister_temporary_file(slot);
    throw;
  }
  unregister_temporary_file(slot);
}

CreatedFolders::CreatedFolders(const std::string& dir) {
  std::error_code ec;
  for (fs::path p(dir); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) created_.push_back(p.string());
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec)) {
    const std::string reason = ec ? ec.message() : "a file of that name is in the way";
    remove_created();
    throw Error(dir + ": cannot create the folder (" + reason + ")");
  }
}

CreatedFolders::~CreatedFolders() { remove_created(); }

void CreatedFolders::remove_created() noexcept {
  for (const std::string& d : created_) {
    std::error_code ec;
    if (!fs::remove(d, ec)) break;  // not empty (or gone): the ones above are not empty either
  }
  created_.clear();
}

OutputTransaction::OutputTransaction() : previous_(t_transaction) { t_transaction = this; }

OutputTransaction::~OutputTransaction() {
  for (const Staged& s : staged_) {
    remove_quietly(s.temp);
    unregister_temporary_file(s.slot);
  }
  t_transaction = previous_;
}

void OutputTransaction::stage(const std::string& temp, const std::string& path, int slot) {
  discard(path);
  staged_.push_back({temp, path, slot});
}

void OutputTransaction::discard(const std::string& path) {
  for (auto it = staged_.begin(); it != staged_.end();) {
    if (it->path == path) {
      remove_quietly(it->temp);
      unregister_temporary_file(it->slot);
      it = staged_.erase(it);
    } else {
      ++it;
    }
  }
}

std::vector<std::string> OutputTransaction::staged() const {
  std::vector<std::string> out;
  for (const Staged& s : staged_) out.push_back(s.path);
  return out;
}

void OutputTransaction::commit() {
  // An interrupt waits until every file is in place, so a signal never leaves half a commit.
  sigset_t block, old;
  sigemptyset(&block);
  for (int sig : kCleanupSignals) sigaddset(&block, sig);
  ::pthread_sigmask(SIG_BLOCK, &block, &old);
  struct Restore {
    sigset_t mask;
    ~Restore() { ::pthread_sigmask(SIG_SETMASK, &mask, nullptr); }
  } restore{old};
  while (!staged_.empty()) {
    const Staged s = staged_.front();
    staged_.erase(staged_.begin());
    try {
      rename_into_place(s.temp, s.path);
    } catch (...) {
      unregister_temporary_file(s.slot);
      throw;  // the destructor removes the ones left
    }
    unregister_temporary_file(s.slot);
  }
}

// ---- Outputs apart from inputs ------------------------------------------------------------------

namespace {

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  // Not both there yet: the same name after resolving the folders that exist.
  const fs::path ca = fs::weakly_canonical(a, ec);
  if (ec) return false;
  const fs::path cb = fs::weakly_canonical(b, ec);
  return !ec && ca == cb;
}

}  // namespace

void check_outputs_apart(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedFile& out = outputs[i];
    if (out.path.empty()) continue;
    for (const NamedFile& in : inputs) {
      if (in.path.empty() || !same_file(out.path, in.path)) continue;
      throw Error(out.path + ": " + out.option + " would overwrite the input given as " + in.option +
                  (in.path == out.path ? "" : " (" + in.path + ")") + "; choose another output");
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (outputs[k].path.empty() || !same_file(out.path, outputs[k].path)) continue;
      throw Error(out.path + ": given as both " + outputs[k].option + " and " + out.option +
                  "; each output needs its own file");
    }
  }
}

// ---- Outputs that can be written --------------------------------------------------------------

namespace {

const char* kind_of(mode_t mode);

std::string option_text(const NamedFile& f) { return f.option.empty() ? std::string() : f.option + " "; }

// The reason a folder cannot take new files ("Permission denied", "Read-only file system"), or
// "" when it can. access(2) also sees a read-only mount, which the permission bits do not show.
std::string unwritable_reason(const fs::path& dir) {
  if (::access(dir.empty() ? "." : dir.c_str(), W_OK | X_OK) == 0) return "";
  return std::strerror(errno);
}

}  // namespace

std::string extension_list(const std::vector<std::string>& extensions) {
  std::string out;
  for (std::size_t i = 0; i < extensions.size(); ++i) {
    if (i > 0) out += i + 1 == extensions.size() ? " or " : ", ";
    out += extensions[i];
  }
  return out;
}

void check_output_file(const NamedFile& output, const std::vector<std::string>& extensions) {
  const std::string& path = output.path;
  if (path.empty()) return;
  const std::string opt = option_text(output);
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(path + ": " + opt + "is a folder, not a file");
    if (!S_ISREG(st.st_mode)) throw Error(path + ": " + opt + "is " + kind_of(st.st_mode) + ", not a regular file");
  }
  if (!extensions.empty() &&
      std::none_of(extensions.begin(), extensions.end(), [&](const std::string& e) { return ends_with_ci(path, e); }))
    throw Error(path + ": " + opt + "must be a " + extension_list(extensions) +
                " file (its extension chooses the format)");
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw Error(path + ": " + (opt.empty() ? "" : output.option + ": ") + "the folder " + parent.string() +
                " does not exist");
  const std::string reason = unwritable_reason(parent);
  if (!reason.empty())
    throw Error(path + ": " + (opt.empty() ? "" : output.option + ": ") + "cannot write into the folder " +
                (parent.empty() ? std::string(".") : parent.string()) + " (" + reason + ")");
}

void check_output_folder(const NamedFile& output) {
  const std::string& path = output.path;
  if (path.empty()) return;
  const std::string opt = option_text(output);
  std::error_code ec;
  fs::path dir(path);
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
    throw Error(path + ": " + opt + "is " + (S_ISREG(st.st_mode) ? "a file" : kind_of(st.st_mode)) + ", not a folder");
  // The folder itself when it exists, else the nearest one above it (where it will be created).
  while (!dir.empty() && !fs::exists(dir, ec)) dir = dir.parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw Error(path + ": " + (opt.empty() ? "" : output.option + ": ") + dir.string() + " is a file, not a folder");
  const std::string reason = unwritable_reason(dir);
  if (!reason.empty())
    throw Error(path + ": " + (opt.empty() ? "" : output.option + ": ") + "cannot write into the folder " +
                (dir.empty() ? std::string(".") : dir.string()) + " (" + reason + ")");
}

long temporary_file_owner(const std::string& name) {
  const std::size_t pos = name.rfind(".tmp");
  if (pos == std::string::npos || pos == 0) return 0;
  const std::string tail = name.substr(pos + 4);
  const std::size_t us = tail.find('_');
  if (us == std::string::npos || us == 0 || us + 1 >= tail.size() || us > 9) return 0;
  if (!std::all_of(tail.begin(), tail.end(), [](char c) { return (c >= '0' && c <= '9') || c == '_'; })) return 0;
  return std::stol(tail.substr(0, us));
}

int remove_stale_temporaries(const std::string& dir, const std::vector<std::string>& extensions) {
  std::error_code ec;
  int removed = 0;
  for (fs::directory_iterator it(dir.empty() ? fs::path(".") : fs::path(dir), ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const long pid = temporary_file_owner(name);
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    const std::string base = name.substr(0, name.rfind(".tmp"));
    if (std::none_of(extensions.begin(), extensions.end(),
                     [&](const std::string& e) { return base.size() > e.size() && ends_with_ci(base, e); }))
      continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM) continue;  // still running
    std::error_code ec2;
    if (fs::remove(it->path(), ec2)) ++removed;
  }
  return removed;
}

std::string temporary_name_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
}

// ---- Reading ------------------------------------------------------------------------------------

namespace {

// What a non-regular file is, for "x: is a FIFO (named pipe), not a regular file".
const char* kind_of(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

void refuse_non_regular(const std::string& path, mode_t mode) {
  if (S_ISREG(mode)) return;
  if (S_ISDIR(mode)) throw Error(path + ": is a folder, not a file");
  const std::string kind = kind_of(mode);
  throw Error(path + ": is " + kind + ", not a regular file");
}

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  FileDescriptor(FileDescriptor&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  FileDescriptor& operator=(FileDescriptor&&) = delete;
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

std::string read_all(const std::string& path, int fd, std::size_t size_hint) {
  std::string bytes;
  bytes.reserve(size_hint);
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error(path + ": read error (" + std::strerror(errno) + ")");
    }
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  return bytes;
}

}  // namespace

void check_input_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) refuse_non_regular(path, st.st_mode);
}

namespace {

// Opens a regular file for reading; *out_size gets its size. Anything else is refused before
// the open, and O_NONBLOCK makes the open return at once should the file have become a FIFO
// since the check (fstat then refuses it).
FileDescriptor open_regular(const std::string& path, std::size_t* out_size) {
  check_input_file(path);
  FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (fd.get() < 0) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  refuse_non_regular(path, st.st_mode);
  *out_size = static_cast<std::size_t>(st.st_size);
  return fd;
}

}  // namespace

void check_readable_file(const std::string& path) {
  std::size_t size = 0;
  open_regular(path, &size);
}

std::string read_file_bytes(const std::string& path) {
  std::size_t size = 0;
  const FileDescriptor fd = open_regular(path, &size);
  return naming_memory_errors(path, "reading " + std::to_string(size) + " bytes",
                              [&] { return read_all(path, fd.get(), size); });
}

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
