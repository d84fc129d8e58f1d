// The output folder of `gmg batch`: created, never an input folder, locked for one batch at a
// time, cleared of the temporary files of a killed run, and its record of the run's settings.
#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include "engine/batch/batch_internal.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/core/strings.h"

namespace gmg::batch {
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

// The same value as an unordered json, to compare with one read from a file.
nlohmann::json plain(const nlohmann::ordered_json& j) { return parse_json_text(json_dump(j, -1), "batch record"); }

}  // namespace

FolderLock::FolderLock(const fs::path& dir, const std::string& name) {
  const std::string path = (dir / ".gmg-batch.lock").string();
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(name + ": cannot create the lock file " + path + " (" + std::strerror(errno) + ")");
  // The file stays empty: the lock is the state, and a refused batch changes nothing.
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw Error(name +
                ": another gmg batch is writing into this output folder; wait for it to finish or choose "
                "another folder");
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

OutputFolder prepare_output_folder(const BatchOptions& options, Progress& progress) {
  OutputFolder out;
  out.dir = fs::path(options.output_dir);
  check_output_folder({"-o", options.output_dir});  // a read-only mount, a file in the way: with the reason
  std::error_code ec;
  fs::create_directories(out.dir, ec);
  if (!fs::is_directory(out.dir, ec))
    throw Error(options.output_dir + ": cannot create the output folder (" +
                (ec ? ec.message() : std::string("a file of that name is in the way")) + ")");
  check_not_an_input_folder(options, out.dir);
  out.lock = std::make_unique<FolderLock>(out.dir, options.output_dir);
  const int removed = remove_stale_temporaries(out.dir.string(), {".bvh", ".json", ".csv"});
  if (removed) progress.line("batch: removed " + std::to_string(removed) + " temporary file(s) of an interrupted run");
  return out;
}

std::string record_difference(const nlohmann::json& old, const nlohmann::json& now) {
  if (!old.is_object() || !now.is_object()) return "an unreadable record";
  // A key's value, null when absent (either record may come from a file).
  const auto field = [](const nlohmann::json& j, const char* key) { return j.value(key, nlohmann::json()); };
  for (const char* key : {"seed", "pairing"})
    if (field(old, key) != field(now, key))
      return std::string(key) + " " + json_dump(field(old, key), -1) + ", not " + json_dump(field(now, key), -1);
  const nlohmann::json pool = field(now, "pool"), old_pool = field(old, "pool");
  if (old_pool != pool)
    return "another pool (" + std::to_string(old_pool.size()) + " reference clips, not " + std::to_string(pool.size()) +
           ")";
  const nlohmann::json params = field(now, "parameters"), old_params = field(old, "parameters");
  if (!old_params.is_object() || !params.is_object()) return "no parameters";
  for (auto it = params.begin(); it != params.end(); ++it)
    if (field(old_params, it.key().c_str()) != it.value())
      return "parameter " + it.key() + " = " + json_dump(field(old_params, it.key().c_str()), -1) + ", not " +
             json_dump(it.value(), -1);
  return "";
}

nlohmann::ordered_json run_record(std::uint64_t seed, BatchPairing pairing, const std::vector<std::string>& pool_stems,
                                  const Config& config) {
  nlohmann::ordered_json record;
  record["tool"] = "gmg batch";
  record["seed"] = seed;
  record["pairing"] = enum_name(kBatchPairingNames, pairing);
  record["pool"] = pool_stems;
  nlohmann::ordered_json parameters = parse_ordered_json_text(config_to_json(config), "the config");
  parameters.erase("seed");
  record["parameters"] = parameters;
  return record;
}

void check_and_write_run_record(const fs::path& out_dir, const std::string& name, const nlohmann::ordered_json& record,
                                const ClipMap& tests, bool force) {
  const fs::path path = out_dir / "batch.json";
  std::error_code ec;
  if (!force && fs::exists(path, ec)) {
    const bool has_outputs = std::any_of(tests.begin(), tests.end(), [&](const auto& t) {
      std::error_code ec2;
      return fs::exists(out_dir / (t.first + ".bvh"), ec2);
    });
    nlohmann::json old;
    try {
      old = read_json_file(path.string());
    } catch (const Error&) {
      old = nullptr;
    }
    const std::string difference = has_outputs ? record_difference(old, plain(record)) : "";
    if (!difference.empty())
      throw Error(name + ": holds outputs of a run with " + difference + " (" + path.string() +
                  "); they would mix with this run's. Use another folder, the same settings, or --force to redo "
                  "every clip");
  }
  const std::string text = json_dump(record, 2) + "\n";
  write_file_atomically(path.string(), [&](std::ostream& os) { os << text; });
}

}  // namespace gmg::batch
