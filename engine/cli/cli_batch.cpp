// The `gmg batch` subcommand: options, interruption by signal, exit codes.
#include <atomic>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "engine/batch/batch.h"
#include "engine/cli/cli_common.h"
#include "engine/core/interrupt.h"
#include "engine/core/strings.h"

namespace gmg {
namespace {

// The names of an enum's table, for CLI::IsMember (so the choices are spelled once).
template <typename E, std::size_t N>
std::vector<std::string> names_of(const EnumName<E> (&table)[N]) {
  std::vector<std::string> out;
  for (const EnumName<E>& e : table) out.emplace_back(e.name);
  return out;
}

// What the command line fills in; the callback turns the texts into options.
struct BatchCliState {
  BatchOptions options;
  std::string config_file;
  std::vector<std::string> sets;
  std::uint64_t seed = 0;
  std::string pairing;
  std::string progress = "auto";
  std::string shard;               // --shard K/N
  std::vector<std::string> merge;  // --merge DIR...
};

void add_clip_options(CLI::App* sub, BatchOptions& o) {
  sub->add_option("--pool", o.pool_dirs,
                  "folder of reference clips (BVH + WAV + optional .tsv/.TextGrid/.json with matching stems, "
                  "flat or in bvh/ wav/ tsv/ subfolders); repeatable");
  sub->add_option("--pool-manifest", o.pool_manifests,
                  "CSV of reference clips with header stem,bvh,wav,transcript; repeatable");
  sub->add_option("--graph", o.graph, "instead of a pool: a graph from 'gmg build', used for every test clip");
  sub->add_option("--tests", o.test_dirs,
                  "folder of test clips (WAV + optional transcript, matching stems); repeatable");
  sub->add_option("--test-manifest", o.test_manifests, "CSV of test clips with header stem,wav,transcript; repeatable");
  sub->add_option("-o,--output", o.output_dir, "output folder (created when missing)")->required();
}

// Runs the batch for the parsed command line; the exit code (see add_batch_command).
int run_batch_command(const BatchCliState& st, bool seed_given, bool shard_given) {
  try {
    if (!st.merge.empty()) {
      const BatchSummary s = batch_merge(st.merge, st.options.output_dir, std::cerr);
      return s.failed > 0 ? 1 : 0;
    }
    const Config config = config_from(st.config_file, st.sets);
    BatchOptions options = st.options;
    if (seed_given) options.seed = st.seed;
    if (shard_given) options.shard = parse_batch_shard(st.shard);  // --shard '' is no part either
    if (!st.pairing.empty()) options.pairing = enum_from_name(kBatchPairingNames, st.pairing).value();
    options.progress = enum_from_name(kBatchProgressNames, st.progress).value_or(BatchProgress::Auto);
    const InterruptFlag interrupt;
    options.cancel = &InterruptFlag::flag();
    const BatchSummary s = batch_run(options, config, std::cerr);
    if (s.interrupted)  // the summary is written: end by the signal (engine/core/interrupt.h)
      throw_if_interrupted("batch", "the clips made are kept; a re-run resumes");
    return s.failed > 0 ? 1 : 0;
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    std::cerr << "gmg: error: " << escape_nonprintable(e.what()) << "\n";
    return 2;
  }
}

}  // namespace

void add_batch_command(CLI::App& app, int* exit_code) {
  CLI::App* sub = app.add_subcommand(
      "batch",
      "reenact many test clips against a pool of references: one BVH per test clip, named after its stem, "
      "plus pairs.csv, summary.csv and summary.json in OUTDIR");
  auto st = std::make_shared<BatchCliState>();
  BatchOptions& o = st->options;
  add_clip_options(sub, o);
  sub->add_option("--pairing", st->pairing, "random (default) or manifest")
      ->check(CLI::IsMember(names_of(kBatchPairingNames)));
  sub->add_option("--manifest", o.pairs_manifest, "CSV test_stem,reference_stem (implies --pairing manifest)");
  sub->add_option("--blacklist", o.blacklist, "file of pool stems to leave out, one a line ('#' comments)");
  CLI::Option* seed_opt =
      whole_number(sub->add_option("--seed", st->seed,
                                   "seed of the pairing draw and of every reenactment (default: the config's seed, " +
                                       std::to_string(Config{}.seed) + ")"))
          ->default_str("");
  whole_number(sub->add_option("--jobs,-j", o.jobs, "parallel clips (default 0: all cores)"), kMaxJobs);
  sub->add_flag("--force", o.force, "redo clips whose output BVH exists");
  sub->add_flag("--reports", o.reports, "also write OUTDIR/<stem>.json, each reenactment's report");
  sub->add_option("--progress", st->progress, "auto (updating line on a terminal), lines, or none")
      ->check(CLI::IsMember(names_of(kBatchProgressNames)));
  CLI::Option* shard_opt =
      sub->add_option("--shard", st->shard,
                      "run part K of N (K/N): every N-th test clip in stem order from the K-th, paired as in one run; "
                      "give each part its own -o folder");
  sub->add_option("--merge", st->merge,
                  "join the summaries of the part folders given (every part of one batch once) into -o OUTDIR")
      ->expected(1, -1);
  sub->add_option("--config", st->config_file, "JSON config file of engine parameters");
  sub->add_option("--set", st->sets, "engine parameter key=value; repeatable");
  sub->callback([st, seed_opt, shard_opt, exit_code] {
    *exit_code = run_batch_command(*st, seed_opt->count() > 0, shard_opt->count() > 0);
  });
}

}  // namespace gmg
