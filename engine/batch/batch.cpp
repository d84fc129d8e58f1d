// batch_run: the steps of a batch in order. The files of each step are listed in
// batch_internal.h.
#include "engine/batch/batch.h"

#include <algorithm>
#include <sstream>

#include "engine/batch/batch_internal.h"
#include "engine/core/error.h"
#include "engine/core/parallel.h"
#include "engine/pipeline/pipeline.h"
#include "graph/graph_io.h"

namespace gmg {
namespace {

using namespace batch;

// The pairing mode after its default, once the options are known to make sense together.
BatchPairing check_options(const BatchOptions& options) {
  if (options.output_dir.empty()) throw Error("batch: no output folder given (-o OUTDIR)");
  if (options.jobs < 0) throw Error("batch: --jobs must be 0 (all cores) or more, got " + std::to_string(options.jobs));
  BatchPairing pairing = options.pairing;
  if (pairing == BatchPairing::Auto)
    pairing = options.pairs_manifest.empty() ? BatchPairing::Random : BatchPairing::Manifest;
  if (pairing == BatchPairing::Manifest && options.pairs_manifest.empty())
    throw Error("batch: --pairing manifest needs --manifest pairs.csv");
  if (pairing == BatchPairing::Random && !options.pairs_manifest.empty())
    throw Error("batch: --manifest " + options.pairs_manifest + " given with --pairing random");
  const bool pool = !options.pool_dirs.empty() || !options.pool_manifests.empty();
  if (!pool && options.graph.empty())
    throw Error("batch: no pool of reference clips given (--pool DIR or --pool-manifest CSV, or --graph G.gmg)");
  if (pool && !options.graph.empty()) throw Error("batch: give either --graph or a pool (--pool, --pool-manifest)");
  if (options.test_dirs.empty() && options.test_manifests.empty())
    throw Error("batch: no test clips given (--tests DIR or --test-manifest CSV)");
  if (options.shard &&
      (options.shard->count < 1 || options.shard->index < 1 || options.shard->index > options.shard->count))
    throw Error("batch: --shard needs K/N with 1 <= K <= N");
  return pairing;
}

// The test clips of one part (see batch.h "Shards"): clip i of the stem-sorted list belongs to
// part i % N + 1. Applied after the pairing draw, so a part pairs as the whole batch does.
Pairing shard_of(const Pairing& all, const BatchShard& shard) {
  Pairing part;
  for (std::size_t i = 0; i < all.test_stems.size(); ++i) {
    if (static_cast<int>(i % static_cast<std::size_t>(shard.count)) != shard.index - 1) continue;
    part.test_stems.push_back(all.test_stems[i]);
    part.references.push_back(all.references[i]);
    part.errors.push_back(all.errors[i]);
  }
  return part;
}

// Every clip's config: the batch's seed (when given) replaces config.seed.
Config clip_config_of(const BatchOptions& options, const Config& config) {
  Config c = config;
  if (options.seed) c.seed = *options.seed;
  config_validate(c);
  return c;
}

// The pool stems left after the blacklist (sorted); counts the others into *blacklisted.
std::vector<std::string> eligible_pool(const ClipMap& pool, const std::set<std::string>& blacklist,
                                       const BatchOptions& options, int* blacklisted) {
  std::vector<std::string> stems;
  for (const auto& [stem, c] : pool) {
    if (blacklist.count(stem)) {
      ++*blacklisted;
      continue;
    }
    stems.push_back(stem);
  }
  if (stems.empty())
    throw Error("batch: the pool is empty after the blacklist (" + std::to_string(*blacklisted) +
                " clips blacklisted by " + options.blacklist + ")");
  return stems;
}

// One result per test clip: skipped when its output exists (unless --force), failed when it
// could not be paired or its files are unusable (ClipFiles::error), else pending.
std::vector<BatchClipResult> initial_results(const Pairing& pairing, const ClipMap& tests, const fs::path& out_dir,
                                             bool force) {
  const std::map<std::string, std::string> previous_pairs = read_previous_pairs(out_dir);
  const std::map<std::string, PreviousClip> previous_clips = read_previous_summary(out_dir);
  std::vector<BatchClipResult> clips(pairing.test_stems.size());
  for (std::size_t i = 0; i < clips.size(); ++i) {
    BatchClipResult& c = clips[i];
    c.test_stem = pairing.test_stems[i];
    c.reference_stem = pairing.references[i];
    c.output = (out_dir / (c.test_stem + ".bvh")).string();
    std::error_code ec;
    if (!force && fs::exists(c.output, ec)) {
      c.status = BatchClipStatus::Skipped;
      c.skipped_existing = true;
      const auto it = previous_pairs.find(c.test_stem);
      if (it != previous_pairs.end()) c.reference_stem = it->second;
      carry_over_previous(c, previous_clips);
    } else if (!pairing.errors[i].empty() || !tests.at(c.test_stem).error.empty()) {
      c.status = BatchClipStatus::Failed;
      c.error = tests.at(c.test_stem).error.empty() ? pairing.errors[i] : tests.at(c.test_stem).error;
      c.output.clear();
    }
  }
  return clips;
}

// The eligible pool, each with the count of pending clips that drew it.
std::vector<BatchReferenceResult> reference_results(const ClipMap& pool, const std::vector<std::string>& pool_stems,
                                                    const std::vector<BatchClipResult>& clips) {
  std::vector<BatchReferenceResult> refs;
  for (const std::string& stem : pool_stems) {
    const ClipFiles& f = pool.at(stem);
    BatchReferenceResult r{f.stem, f.bvh, f.wav, f.transcript, 0, 0, 0.0, ""};
    for (const BatchClipResult& c : clips)
      if (c.status == BatchClipStatus::Pending && c.reference_stem == stem) ++r.clips;
    refs.push_back(std::move(r));
  }
  return refs;
}

std::size_t pending_count(const std::vector<BatchClipResult>& clips) {
  return static_cast<std::size_t>(std::count_if(
      clips.begin(), clips.end(), [](const BatchClipResult& c) { return c.status == BatchClipStatus::Pending; }));
}

// The lines before any work: notes, what will be done, the clips already decided. Returns how
// many clips are already decided (failed or skipped).
std::size_t announce(const BatchSummary& summary, const Clips& clips, BatchPairing pairing, std::size_t pool_size,
                     Progress& progress) {
  const std::size_t total = summary.clips.size(), to_do = pending_count(summary.clips);
  for (const std::string& n : clips.notes) progress.line("batch: note: " + n);
  std::ostringstream os;
  os << "batch: " << total << " test clips";
  if (summary.shard)
    os << " (part " << summary.shard->index << "/" << summary.shard->count << " of " << summary.batch_clips << ")";
  if (to_do != total) os << " (" << total - to_do << " skipped or unpaired)";
  os << ", pool of " << pool_size << " reference clips";
  if (summary.blacklisted) os << " (" << summary.blacklisted << " blacklisted)";
  os << ", pairing " << enum_name(kBatchPairingNames, pairing) << ", seed " << summary.seed << ", " << summary.jobs
     << (summary.jobs == 1 ? " job" : " jobs");
  progress.line(os.str());
  std::size_t finished = 0, skipped = 0;
  for (const BatchClipResult& c : summary.clips) {
    if (c.status == BatchClipStatus::Skipped) ++skipped;
    if (c.status == BatchClipStatus::Failed) {
      ++finished;
      progress.line("[" + std::to_string(finished) + "/" + std::to_string(total) + "] " + c.test_stem +
                    " FAILED: " + c.error);
    }
  }
  if (skipped)
    progress.line("batch: " + std::to_string(skipped) + " clip(s) skipped: output exists (--force redoes them)");
  return finished + skipped;
}

}  // namespace

BatchSummary batch_run(const BatchOptions& options, const Config& config, std::ostream& progress_stream) {
  const Clock::time_point t_start = Clock::now();
  Progress progress(progress_stream, options.progress);
  BatchSummary summary;

  const BatchPairing pairing = check_options(options);
  const Config clip_config = clip_config_of(options, config);
  summary.seed = clip_config.seed;

  const Clips clips = collect_clips(options);
  summary.notes = clips.notes;
  std::set<std::string> blacklist;
  if (!options.blacklist.empty()) blacklist = read_blacklist(options.blacklist);
  const std::vector<std::string> pool_stems = eligible_pool(clips.pool, blacklist, options, &summary.blacklisted);
  // A --graph is read before anything is written: a file that is not a graph (or lacks a joint
  // lock_joints names) stops the batch, as `gmg reenact --graph` stops, rather than failing
  // every clip. Its motion is checked where it is played (MotionCheck::OnUse).
  std::shared_ptr<const MotionGraph> graph;
  const Clock::time_point t_graph = Clock::now();
  if (!options.graph.empty()) {
    graph = std::make_shared<const MotionGraph>(graph_load(options.graph, MotionCheck::OnUse));
    check_lock_joints_of_graph(*graph, clip_config, options.graph);
  }
  const double graph_seconds = seconds_since(t_graph);
  const OutputFolder out = prepare_output_folder(options, progress);  // locked until the end of the run
  const fs::path& out_dir = out.dir;
  check_and_write_run_record(out_dir, options.output_dir,
                             run_record(clip_config.seed, pairing, pool_stems, clip_config), clips.tests,
                             options.force);

  const Pairing all_pairs = pair_tests(options, pairing, clips, blacklist, pool_stems, clip_config.seed);
  summary.batch_clips = static_cast<int>(all_pairs.test_stems.size());
  summary.shard = options.shard;
  const Pairing pairs = options.shard ? shard_of(all_pairs, *options.shard) : all_pairs;
  summary.clips = initial_results(pairs, clips.tests, out_dir, options.force);
  summary.references = reference_results(clips.pool, pool_stems, summary.clips);
  write_pairs_csv(out_dir, summary.clips);  // first, so the pairing is on record even if the run is interrupted

  summary.jobs = worker_count(options.jobs);
  const std::size_t finished = announce(summary, clips, pairing, pool_stems.size(), progress);
  const int workers = worker_count(summary.jobs, pending_count(summary.clips));
  run_clips(summary, RunSetup{options, clip_config, clips.tests, out_dir, progress, graph, graph_seconds}, workers,
            finished);
  progress.finish();

  count_statuses(summary);
  summary.interrupted = options.cancel && options.cancel->load();
  for (const BatchReferenceResult& r : summary.references) summary.graph_seconds += r.build_seconds;
  summary.seconds = seconds_since(t_start);
  write_summary_files(out_dir, summary, options, pairing);
  progress.line(summary_line(summary, out_dir));
  return summary;
}

}  // namespace gmg
