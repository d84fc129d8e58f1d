// The progress display of `gmg batch` and `gmg build --clips`.
#pragma once

#include <cstddef>
#include <mutex>
#include <ostream>
#include <string>

#include "engine/batch/batch.h"

namespace gmg::batch {

// Lines that stay and, on a terminal, one updating status line below them. Thread-safe.
class Progress {
 public:
  Progress(std::ostream& os, BatchProgress mode);

  // A line that stays.
  void line(const std::string& s);
  // The updating status line (on a terminal), else `plain` as a line.
  void status(const std::string& short_text, const std::string& plain);
  // Ends the status line.
  void finish();

 private:
  std::size_t columns() const;

  std::ostream& os_;
  bool terminal_ = false, quiet_ = false;
  int fd_ = -1;
  std::mutex m_;
  std::string status_;
};

}  // namespace gmg::batch
