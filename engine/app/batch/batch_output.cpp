// The output folder of `gmg batch`: created, never an input folder, cleared of the temporary
// files of a killed run.
#include <algorithm>
#include <cerrno>

#include <signal.h>
#include <unistd.h>

#include "engine/app/batch/batch_internal.h"
#include "engine/core/error.h"
#include "engine/core/strings.h"

namespace gmg::batch_internal {
namespace {

void check_not_an_input_folder(const BatchOptions& options, const fs::path& out_dir) {
  for (const std::vector<std::string>* dirs : {&options.pool_dirs, &options.test_dirs})
    for (const std::string& d : *dirs)
      for (const fs::path& p : {fs::path(d), fs::path(d) / "bvh", fs::path(d) / "wav"}) {
        std::error_code ec;
        if (fs::exists(p, ec) && fs::equivalent(p, out_dir, ec))
          throw Error(options.output_dir + ": the output folder is an input folder; choose another");
      }
}

// The process id of a temporary file "<name>.tmp<pid>_<n>" (write_file_atomically's names) of
// a BVH, JSON or CSV output; 0 for any other file.
long temporary_file_pid(const std::string& name) {
  const std::size_t pos = name.rfind(".tmp");
  if (pos == std::string::npos || pos == 0) return 0;
  const std::string base = name.substr(0, pos);
  auto named = [&](std::string_view ext) { return base.size() > ext.size() && ends_with_ci(base, ext); };
  if (!named(".bvh") && !named(".json") && !named(".csv")) return 0;
  const std::string tail = name.substr(pos + 4);
  const std::size_t us = tail.find('_');
  if (us == std::string::npos || us == 0 || us + 1 >= tail.size()) return 0;
  if (!std::all_of(tail.begin(), tail.end(), [](char c) { return (c >= '0' && c <= '9') || c == '_'; })) return 0;
  try {
    return std::stol(tail.substr(0, us));
  } catch (...) {
    return 0;
  }
}

// Removes the temporary files of processes that are gone (a live one may be another batch).
void remove_stale_temporaries(const fs::path& dir, Progress& progress) {
  std::error_code ec;
  int removed = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const long pid = temporary_file_pid(it->path().filename().string());
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM) continue;  // still running
    std::error_code ec2;
    if (fs::remove(it->path(), ec2)) ++removed;
  }
  if (removed) progress.line("batch: removed " + std::to_string(removed) + " temporary file(s) of an interrupted run");
}

}  // namespace

fs::path prepare_output_folder(const BatchOptions& options, Progress& progress) {
  const fs::path out_dir(options.output_dir);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir, ec)) throw Error(options.output_dir + ": cannot create the output folder");
  check_not_an_input_folder(options, out_dir);
  remove_stale_temporaries(out_dir, progress);
  return out_dir;
}

}  // namespace gmg::batch_internal
