#include "engine/core/files.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "engine/core/error.h"

namespace gmg {
namespace fs = std::filesystem;

// ---- Interruption -------------------------------------------------------------------------------

namespace {

constexpr int kSlots = 256;
constexpr std::size_t kPathBytes = 4096;

// state: 0 free, 1 being filled (skipped by the handler), 2 registered.
struct TemporarySlot {
  std::atomic<int> state{0};
  char path[kPathBytes];
};
TemporarySlot g_temporaries[kSlots];

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void cleanup_and_die(int sig) { remove_temporaries_and_die(sig); }

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

InterruptCleanup::InterruptCleanup() : saved_(new Saved) {
  struct sigaction sa {};
  sa.sa_handler = cleanup_and_die;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  for (std::size_t i = 0; i < std::size(kCleanupSignals); ++i) ::sigaction(kCleanupSignals[i], &sa, &saved_->old[i]);
}

InterruptCleanup::~InterruptCleanup() {
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

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool binary) {
  static std::atomic<unsigned> counter{0};
  const std::string temp = path + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
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
    out.flush();
    if (!out) {
      out.close();
      abandon();
      throw Error(path + ": write failed (disk full or unwritable?)");
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

MappedFile::MappedFile(const std::string& path) {
  const FileDescriptor fd = open_regular(path, &size_);
  if (size_ == 0) return;
  void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd.get(), 0);
  if (p == MAP_FAILED) throw Error(path + ": cannot read (" + std::strerror(errno) + ")");
  data_ = static_cast<const char*>(p);
  ::madvise(p, size_, MADV_SEQUENTIAL);  // readers go through the file once, front to back
}

MappedFile::~MappedFile() {
  if (data_) ::munmap(const_cast<char*>(data_), size_);
}

}  // namespace gmg
