// Internals of `gmg batch` shared by its files; the interface is batch.h, with batch_clips.h
// and batch_progress.h (which `gmg build --clips` uses too).
//
//   batch.cpp           batch_run: the steps in order (options, clips, pairing, results, run,
//                       records)
//   batch_clips.cpp     clip discovery: folders (flat and GENEA subfolders), clip manifests
//   batch_pairing.cpp   the pairing draw, the blacklist, the pairs manifest and pairs.csv
//   batch_output.cpp    the output folder: checks and stale temporary files
//   batch_progress.cpp  the progress display
//   batch_schedule.cpp  the workers: graph builds shared by the clips that drew them
//   batch_summary.cpp   summary.csv/summary.json, and the previous run's figures
//   batch_merge.cpp     joining the summaries of parts made with --shard
//
// The `batch` subcommand itself is the command line's (engine/cli/cli_batch.cpp).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/batch/batch.h"
#include "engine/batch/batch_clips.h"
#include "engine/batch/batch_progress.h"

namespace gmg {
struct MotionGraph;
}  // namespace gmg

namespace gmg::batch {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// v with `decimals` digits after the point ("1.50"), for progress lines and summary.csv.
std::string fixed(double v, int decimals);

// ---- Pairing (batch_pairing.cpp) ------------------------------------------------------------

// Pool stems listed in a blacklist file (see batch.h).
std::set<std::string> read_blacklist(const std::string& path);

// A pairs manifest: test stem -> reference stem. With `strict`, malformed rows and a test paired
// twice are errors naming the file and line; otherwise they are skipped (the last pair wins).
std::map<std::string, std::string> read_pairs(const std::string& path, bool strict);

// The reference of each test clip (in stem order); error[i] non-empty when test i cannot be
// paired (that clip fails, the others go on).
struct Pairing {
  std::vector<std::string> test_stems, references, errors;
};

// Pairs the test clips by `mode` (Random or Manifest) with `pool_stems` (sorted, blacklist
// removed). Throws gmg::Error when the pairs manifest cannot be read or names an unknown test.
Pairing pair_tests(const BatchOptions& options, BatchPairing mode, const Clips& clips,
                   const std::set<std::string>& blacklist, const std::vector<std::string>& pool_stems,
                   std::uint64_t seed);

// The pairs of a previous run's OUTDIR/pairs.csv (empty when there is none or it is unreadable).
std::map<std::string, std::string> read_previous_pairs(const fs::path& out_dir);

// OUTDIR/pairs.csv: test_stem,reference_stem for every paired clip.
void write_pairs_csv(const fs::path& out_dir, const std::vector<BatchClipResult>& clips);

// ---- Output folder (batch_output.cpp) -------------------------------------------------------

// An exclusive lock (flock) on OUTDIR/.gmg-batch.lock, held while alive: two batches never write
// into one folder at once. The lock goes with the process, however it ends.
class FolderLock {
 public:
  // Throws gmg::Error naming the folder when another process holds the lock.
  FolderLock(const fs::path& dir, const std::string& name);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

struct OutputFolder {
  fs::path dir;
  std::unique_ptr<FolderLock> lock;
};

// Creates OUTDIR, refuses one that is an input folder or in use by another batch (and locks it
// for this one), removes stale temporary files of a killed run (reported on `progress`).
OutputFolder prepare_output_folder(const BatchOptions& options, Progress& progress);

// OUTDIR/batch.json, the record of what the folder's outputs were made with: seed, pairing,
// pool stems and parameters. Written before any clip starts.
nlohmann::ordered_json run_record(std::uint64_t seed, BatchPairing pairing, const std::vector<std::string>& pool_stems,
                                  const Config& config);

// What differs between two run records (run_record, or a batch.json read back), in words ("seed
// 1, not 2", "another pool (3 reference clips, not 1)", "parameter l_pn = 5, not 7"); "" when
// nothing does.
std::string record_difference(const nlohmann::json& old, const nlohmann::json& now);

// Throws gmg::Error when OUTDIR holds outputs of a test clip of this run (which would be skipped)
// and its batch.json records another seed, pairing, pool or parameters, unless `force` (every
// clip is then redone): outputs of two settings would mix silently. Then writes `record`.
void check_and_write_run_record(const fs::path& out_dir, const std::string& name, const nlohmann::ordered_json& record,
                                const ClipMap& tests, bool force);

// ---- Summary (batch_summary.cpp) ------------------------------------------------------------

// A clip's figures in a previous run's summary.json.
struct PreviousClip {
  std::optional<BatchClipStatus> status;
  std::string reference;
  double frames = 0, fallbacks = 0, failures = 0, seconds = 0;
};

// The clips of OUTDIR/summary.json by test stem (empty when there is none or it is unreadable).
std::map<std::string, PreviousClip> read_previous_summary(const fs::path& out_dir);

// A skipped clip takes its frames..seconds from the previous run when that made it (ok or
// skipped) with the same reference, so a resumed run's summary still covers every clip.
void carry_over_previous(BatchClipResult& clip, const std::map<std::string, PreviousClip>& previous);

// Pending clips become cancelled; counts the statuses into summary.ok..cancelled.
void count_statuses(BatchSummary& summary);

// OUTDIR/summary.csv and OUTDIR/summary.json.
void write_summary_files(const fs::path& out_dir, const BatchSummary& summary, const BatchOptions& options,
                         BatchPairing pairing);

// A summary.json as batch wrote it, with the two fields the summary itself does not hold.
struct RecordedSummary {
  BatchSummary summary;  // clips, references, seed, jobs, times, shard, batch_clips
  std::string pairing;   // "random" or "manifest"
  std::string blacklist;
};

// Reads a summary.json written by write_summary_files. Throws gmg::Error naming the file when
// it is unreadable or not a batch summary.
RecordedSummary read_summary_file(const fs::path& path);

// The last progress line: counts, times and where the summary is.
std::string summary_line(const BatchSummary& summary, const fs::path& out_dir);

// ---- Scheduling (batch_schedule.cpp) --------------------------------------------------------

struct RunSetup {
  const BatchOptions& options;
  const Config& config;  // every clip's (the seed applied)
  const ClipMap& tests;
  const fs::path& out_dir;
  Progress& progress;
  // The --graph, loaded before the run (a file that is not a graph is a setup error, not a
  // failure of every clip), and the seconds its load took; null without --graph.
  std::shared_ptr<const MotionGraph> graph{};
  double graph_seconds = 0;
};

// Makes every pending clip of summary.clips with `workers` threads, building each
// reference of summary.references once, when the first clip needing it starts. `finished` is
// the count of clips already decided (for the "[k/N]" lines). Stops starting work when
// options.cancel is raised.
void run_clips(BatchSummary& summary, const RunSetup& setup, int workers, std::size_t finished);

}  // namespace gmg::batch
