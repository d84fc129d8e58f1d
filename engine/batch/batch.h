// `gmg batch`: reenact many test speeches against a pool of reference clips (the paper's
// GENEA 2023 protocol, section 5.1.1), in parallel, resumably.
//
// Inputs
// - Pool clips (references): BVH + WAV + optional transcript. Test clips: WAV + optional
//   transcript (a BVH beside a test WAV, e.g. ground truth, is ignored).
// - A clip folder (`--pool DIR`, `--tests DIR`, both repeatable) holds files with matching stems,
//   either flat (DIR/a.bvh, DIR/a.wav, DIR/a.tsv) or GENEA-style in subfolders (DIR/bvh/a.bvh,
//   DIR/wav/a.wav, DIR/tsv/a.tsv); both may be mixed. The subfolders looked into are named
//   bvh, wav, tsv, textgrid, json, transcript, transcripts (any case). Extensions are matched
//   ignoring case: .bvh, .wav, and transcripts .tsv (preferred), .TextGrid, .json. Pool stems
//   need a BVH and a WAV (a BVH without WAV is reported and left out; a WAV without BVH is a
//   test clip and ignored in a pool); test stems need a WAV. Audio in another format (.flac,
//   .mp3, .ogg, .oga, .opus, .m4a, .aac, .aif, .aiff) stands in for a missing WAV. A test stem
//   with a transcript but no audio, and a test file that is a broken symbolic link, fail that
//   clip with the reason in the summary; a pool file that is a broken link is noted and fails
//   the clips that draw it. The same stem found twice (in two folders or two layouts) is a
//   setup error.
// - A clip manifest (`--pool-manifest`, `--test-manifest`, repeatable) is a CSV with a header
//   row naming its columns: `stem`, `bvh` (alias `motion`), `wav` (alias `audio`), `transcript`
//   (alias `tsv`, `textgrid`). `stem` defaults to the WAV's (tests) or BVH's (pool) file stem;
//   an empty transcript or "none" means none; relative paths are relative to the manifest's
//   folder. Lines starting with '#' and blank lines are skipped; fields may be "quoted".
//   Missing files are not a setup error: they fail the clips that need them.
//
// - A built graph (`--graph G.gmg`, instead of a pool): every test clip is reenacted from it. It
//   is loaded once, before the output folder is made, and shared by all workers (a graph of hours
//   of reference, built with `gmg build --clips`, is not copied per clip); a file that is not a
//   usable graph (or lacks a joint lock_joints names) is a setup error. Its stem is the clips'
//   reference in pairs.csv.
//
// Pairing
// - random (default): pool minus blacklist, sorted by stem. Test clips are taken in stem order
//   and each draws `candidates[rng() % candidates.size()]` from one std::mt19937_64(seed), where
//   candidates excludes a pool clip with the test's own stem (that would copy the ground
//   truth). One draw per test clip, also for clips skipped because their output exists, so the
//   pairing depends only on the seed, the pool, the blacklist and the test stems; never on
//   --jobs or scheduling.
// - manifest: a CSV `test_stem,reference_stem` (optional header row with those names, '#'
//   comments). A test clip absent from it, or paired with a stem that is not in the pool or is
//   blacklisted, fails (only that clip); a manifest row naming an unknown test is a setup
//   error. OUTDIR/pairs.csv of a previous run is such a manifest.
// - Blacklist: one stem per line ('#' starts a comment; a file name or path is accepted, its
//   folder and a .bvh/.wav/.tsv/.textgrid/.json extension are dropped). It removes pool clips
//   only.
//
// Work
// - Each reference's graph is built once, when the first clip needing it starts, and shared by
//   every clip that drew it; it is released when the last of them has finished. A worker with
//   nothing else to do never waits for a graph another worker builds while a clip with a ready
//   graph or an unbuilt one is left, so at most about `jobs` graphs are in memory at once.
// - Every reenactment uses the same seed (`--seed`, else config.seed), so a clip's output does not
//   depend on scheduling and equals `gmg reenact --graph G --seed N` with G built from its
//   reference alone.
// - Outputs: OUTDIR/<test_stem>.bvh (in the reference's skeleton; written to a temporary name and
//   renamed, so an interrupted run leaves no truncated BVH), optional OUTDIR/<test_stem>.json
//   (the reenactment report, with --reports), OUTDIR/pairs.csv (test_stem,reference_stem; written
//   before any clip starts), OUTDIR/summary.csv and OUTDIR/summary.json (written at the end).
//   A clip whose BVH exists is skipped unless --force (its reference in pairs.csv is the one the
//   previous pairs.csv recorded, when it did; its frames, fallbacks, failures and seconds in the
//   summary are the previous summary.json's, when it recorded them). Stale temporary files of a killed run (of a
//   process no longer alive) are removed. A clip's BVH and report are written together or not at all.
// - One batch at a time per folder: OUTDIR/.gmg-batch.lock is locked (flock) for the whole run, so
//   a second batch into it is a setup error. OUTDIR/batch.json records the seed, pairing, pool
//   stems and parameters; a re-run whose settings differ while the folder holds outputs of its
//   test clips is a setup error naming the difference (outputs of both would mix), unless --force.
// - Stems name outputs, so a stem must be a plain file name: a manifest stem with a '/'
//   ("../escaped") is a setup error naming the manifest line.
// - A clip that cannot be made (unreadable input, broken reference, ...) fails with its error
//   text in the summary; the others complete.
//
// Shards (for a cluster: scripts/slurm_batch.sh, or GNU parallel)
// - `--shard K/N` runs part K of N: test clip i of the stem-sorted list (from 0) belongs to part
//   i % N + 1. The pairing is drawn over all test clips before the split, so a part pairs and
//   writes exactly what one run of the whole batch would for its clips (the union of the parts'
//   BVH and JSON outputs is byte-identical to a single run's). A part's OUTDIR holds its clips
//   only: outputs, pairs.csv rows, and a summary.json that records "shard": {"index": K,
//   "count": N, "batch_clips": all test clips}. Give each part its own OUTDIR.
// - `--merge DIR... -o OUTDIR` joins the parts' summaries into OUTDIR/summary.csv, summary.json
//   and pairs.csv (clips by test stem), and puts every part's outputs (BVH and report) into
//   OUTDIR too, hard-linked when on the same file system, else copied, so OUTDIR holds the whole
//   batch as one run would (each clip's output path names its copy there). It needs every part
//   1..N of one batch exactly once (same N, seed, pairing and clip count, the same references:
//   the same pool or the same --graph, and the same parameters in each part's batch.json), no
//   test clip in two parts, every output a part's summary lists, and an OUTDIR that is none of
//   the parts, holds none and lies in none; otherwise it stops with an error naming the folders
//   and what differs, before it writes anything. What it writes appears together (staged, then
//   renamed into place), so a merge that fails leaves OUTDIR as it was.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "engine/config/config.h"
#include "engine/core/enum_names.h"

namespace gmg {

enum class BatchProgress {
  Auto,      // a single updating line when the stream is std::cerr/std::clog (std::cout) and
             // stderr (stdout) is a terminal, else plain lines
  Terminal,  // always the updating line
  Lines,     // always plain lines
  Quiet,     // nothing
};
// The choices of `gmg batch --progress` (Terminal is for tests: a pipe cannot be a terminal).
inline constexpr EnumName<BatchProgress> kBatchProgressNames[] = {
    {BatchProgress::Auto, "auto"}, {BatchProgress::Lines, "lines"}, {BatchProgress::Quiet, "none"}};

enum class BatchPairing {
  Auto,      // Manifest when BatchOptions::pairs_manifest is set, else Random
  Random,    // the seeded draw (batch_draw_references)
  Manifest,  // the pairs of BatchOptions::pairs_manifest
};
// The choices of `gmg batch --pairing`, and the names in the summary and progress lines.
inline constexpr EnumName<BatchPairing> kBatchPairingNames[] = {{BatchPairing::Random, "random"},
                                                                {BatchPairing::Manifest, "manifest"}};

enum class BatchClipStatus {
  Pending,    // not decided yet; never left in a returned summary
  Ok,         // made
  Failed,     // could not be made (BatchClipResult::error says why)
  Skipped,    // its output existed (and --force was not given)
  Cancelled,  // not started: the run was interrupted
};
// The names in summary.csv and summary.json.
inline constexpr EnumName<BatchClipStatus> kBatchClipStatusNames[] = {{BatchClipStatus::Pending, "pending"},
                                                                      {BatchClipStatus::Ok, "ok"},
                                                                      {BatchClipStatus::Failed, "failed"},
                                                                      {BatchClipStatus::Skipped, "skipped"},
                                                                      {BatchClipStatus::Cancelled, "cancelled"}};

// Part `index` (1-based) of `count` parts of a batch (see "Shards" above).
struct BatchShard {
  int index = 1, count = 1;
};

// "K/N" with 1 <= K <= N; gmg::Error otherwise.
BatchShard parse_batch_shard(const std::string& text);

struct BatchOptions {
  std::vector<std::string> pool_dirs;         // --pool DIR (repeatable)
  std::string graph;                          // --graph G.gmg: every test clip from this graph (no pool)
  std::vector<std::string> pool_manifests;    // --pool-manifest CSV (repeatable)
  std::vector<std::string> test_dirs;         // --tests DIR (repeatable)
  std::vector<std::string> test_manifests;    // --test-manifest CSV (repeatable)
  std::string output_dir;                     // -o OUTDIR (created when missing)
  BatchPairing pairing = BatchPairing::Auto;  // --pairing
  std::string pairs_manifest;                 // --manifest pairs.csv
  std::string blacklist;                      // --blacklist FILE ("" = none)
  std::optional<std::uint64_t> seed;          // --seed: pairing draw and reenactment; unset = config.seed
  int jobs = 0;                               // --jobs: worker threads; 0 = all cores
  bool force = false;                         // --force: redo clips whose output exists
  bool reports = false;                       // --reports: also write OUTDIR/<stem>.json
  BatchProgress progress = BatchProgress::Auto;
  std::optional<BatchShard> shard;  // --shard K/N: only that part's test clips
  // When set and it becomes true, no further clip or graph build starts; clips under way finish,
  // the summary is written (remaining clips "cancelled") and BatchSummary::interrupted is true.
  const std::atomic<bool>* cancel = nullptr;
};

struct BatchClipResult {
  std::string test_stem, reference_stem, output, error;
  BatchClipStatus status = BatchClipStatus::Pending;
  int frames = 0, fallbacks = 0, failures = 0;  // the reenactment's frames and its plan's
                                                // fallback and failure counts
  double seconds = 0;                           // this clip's own work (speech analysis, search, writing); not the
                                                // graph build and not time spent waiting for it. For a skipped clip,
                                                // frames..seconds are the previous run's (0 when unknown).
  bool skipped_existing = false;
};

struct BatchReferenceResult {
  std::string stem, motion, audio, transcript;
  int clips = 0;             // test clips that drew it (and were not skipped)
  int frames = 0;            // graph frames (0 when not built)
  double build_seconds = 0;  // graph build time (0 when not built)
  std::string error;         // build error, "" when fine or not built
};

struct BatchSummary {
  std::vector<BatchClipResult> clips;            // sorted by test stem
  std::vector<BatchReferenceResult> references;  // pool after the blacklist, sorted by stem
  int ok = 0, failed = 0, skipped = 0, cancelled = 0;
  int blacklisted = 0;  // pool clips removed by the blacklist
  int jobs = 1;         // worker threads used
  std::uint64_t seed = 0;
  double seconds = 0;               // wall time of the whole run
  double graph_seconds = 0;         // sum of graph build times
  bool interrupted = false;         // options.cancel was raised
  std::optional<BatchShard> shard;  // the part this run made (clips holds its clips only)
  int batch_clips = 0;              // test clips of the whole batch (every part)
  std::vector<std::string> parts;   // batch_merge: the part folders joined
  // Files found but not used or unusable (a pool BVH without audio, a broken symbolic link), as
  // the first progress lines said them.
  std::vector<std::string> notes;
};

// Runs a batch. Progress goes to `progress`. Throws gmg::Error on a setup problem (no pool or test
// clips, an unreadable manifest or blacklist, a duplicate stem, an empty pool after the
// blacklist, a bad option, an unusable output folder); per-clip problems are reported in the
// summary instead.
BatchSummary batch_run(const BatchOptions& options, const Config& config, std::ostream& progress);

// Joins the summaries of parts made with --shard (each folder's summary.json) into out_dir's
// summary.csv, summary.json and pairs.csv (see "Shards"); returns the joined summary. Throws
// gmg::Error naming the folders, before writing anything, when a part is missing, given twice,
// from another batch or setup, lacks an output its summary lists, or shares a test clip with
// another, or when out_dir is, holds or lies in a part.
BatchSummary batch_merge(const std::vector<std::string>& part_dirs, const std::string& out_dir, std::ostream& progress);

// The pairing draw (exposed for tests): for each test stem in the given order, one draw from
// `pool` (sorted, blacklist already removed) without the test's own stem; "" when no candidate is
// left.
std::vector<std::string> batch_draw_references(const std::vector<std::string>& test_stems,
                                               const std::vector<std::string>& pool, std::uint64_t seed);

}  // namespace gmg
