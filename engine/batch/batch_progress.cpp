// The progress display of `gmg batch`.
#include <iostream>

#include <sys/ioctl.h>
#include <unistd.h>

#include "engine/batch/batch_internal.h"

namespace gmg::batch {

Progress::Progress(std::ostream& os, BatchProgress mode) : os_(os) {
  if (mode == BatchProgress::Auto) {
    if (&os == &std::cerr || &os == &std::clog)
      fd_ = 2;
    else if (&os == &std::cout)
      fd_ = 1;
    terminal_ = fd_ >= 0 && ::isatty(fd_) != 0;
  } else {
    terminal_ = mode == BatchProgress::Terminal;
    quiet_ = mode == BatchProgress::Quiet;
  }
}

void Progress::line(const std::string& s) {
  if (quiet_) return;
  std::lock_guard<std::mutex> lock(m_);
  if (terminal_) {
    os_ << "\r\x1b[K" << s << "\n";
    if (!status_.empty()) os_ << status_;
  } else {
    os_ << s << "\n";
  }
  os_.flush();
}

void Progress::status(const std::string& short_text, const std::string& plain) {
  if (quiet_) return;
  std::lock_guard<std::mutex> lock(m_);
  if (terminal_) {
    status_ = short_text;
    const std::size_t width = columns();
    if (width > 1 && status_.size() >= width) status_.resize(width - 1);  // a wrapped line cannot be redrawn
    os_ << "\r\x1b[K" << status_;
  } else {
    os_ << plain << "\n";
  }
  os_.flush();
}

void Progress::finish() {
  if (quiet_) return;
  std::lock_guard<std::mutex> lock(m_);
  if (terminal_ && !status_.empty()) os_ << "\n";
  status_.clear();
  os_.flush();
}

std::size_t Progress::columns() const {
  struct winsize w {};
  if (fd_ >= 0 && ::ioctl(fd_, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
  return 80;
}

}  // namespace gmg::batch
