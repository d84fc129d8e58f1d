#include "engine/core/file_write.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <signal.h>
#include <unistd.h>

#include "engine/core/error.h"
#include "engine/core/interrupt.h"
#include "engine/core/strings.h"

namespace gmg {
namespace fs = std::filesystem;

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

}  // namespace gmg
