// Parts of a batch (--shard K/N) and joining their summaries (--merge), see batch.h "Shards".
#include <algorithm>
#include <map>

#include "engine/batch/batch_internal.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"

namespace gmg {

BatchShard parse_batch_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  const auto bad = [&] { return Error("--shard expects K/N with 1 <= K <= N, got '" + text + "'"); };
  if (slash == std::string::npos) throw bad();
  const std::optional<double> k = parse_number(text.substr(0, slash)), n = parse_number(text.substr(slash + 1));
  if (!k || !n || *k != static_cast<int>(*k) || *n != static_cast<int>(*n) || *k < 1 || *k > *n || *n > 1e6)
    throw bad();
  return {static_cast<int>(*k), static_cast<int>(*n)};
}

namespace {

using namespace batch;

struct Part {
  std::string dir;
  RecordedSummary record;
};

std::string part_name(const BatchShard& s) { return std::to_string(s.index) + "/" + std::to_string(s.count); }

// Every part of one batch, exactly once.
void check_parts(const std::vector<Part>& parts) {
  const Part& first = parts.front();
  if (!first.record.summary.shard)
    throw Error(first.dir + ": its summary.json is not a part's (made without --shard K/N)");
  const int count = first.record.summary.shard->count;
  std::map<int, std::string> seen;
  for (const Part& p : parts) {
    const BatchSummary& s = p.record.summary;
    if (!s.shard) throw Error(p.dir + ": its summary.json is not a part's (made without --shard K/N)");
    const std::string what = p.dir + " (part " + part_name(*s.shard) + ")";
    if (s.shard->count != count || s.seed != first.record.summary.seed || p.record.pairing != first.record.pairing ||
        s.batch_clips != first.record.summary.batch_clips)
      throw Error("batch --merge: " + what + " is not from the same batch as " + first.dir + " (part " +
                  part_name(*first.record.summary.shard) + "): parts must share N, seed, pairing and clips");
    const auto [it, inserted] = seen.emplace(s.shard->index, p.dir);
    if (!inserted)
      throw Error("batch --merge: part " + part_name(*s.shard) + " is given twice: " + it->second + " and " + p.dir);
  }
  std::string missing;
  for (int k = 1; k <= count; ++k)
    if (!seen.count(k)) missing += (missing.empty() ? "" : ", ") + std::to_string(k) + "/" + std::to_string(count);
  if (!missing.empty())
    throw Error("batch --merge: missing part(s) " + missing + " (got " + std::to_string(parts.size()) + " of " +
                std::to_string(count) + ")");
}

// The references of all parts by stem: clip counts and build times add up.
void add_references(BatchSummary& merged, const BatchSummary& part) {
  for (const BatchReferenceResult& r : part.references) {
    const auto it = std::find_if(merged.references.begin(), merged.references.end(),
                                 [&](const BatchReferenceResult& m) { return m.stem == r.stem; });
    if (it == merged.references.end()) {
      merged.references.push_back(r);
      continue;
    }
    it->clips += r.clips;
    it->frames = std::max(it->frames, r.frames);
    it->build_seconds += r.build_seconds;
    if (it->error.empty()) it->error = r.error;
  }
}

// `from` at `to`, whole or not at all: a hard link when both are on one file system (no copy of
// hours of motion), else a copy; an existing `to` is replaced. Nothing when they are one file.
void place_file(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  if (fs::exists(to, ec) && fs::equivalent(from, to, ec)) return;
  const std::string temp = temporary_name_for(to.string());
  fs::create_hard_link(from, temp, ec);
  if (ec) {
    ec.clear();
    fs::copy_file(from, temp, ec);
    if (ec) {
      const std::string reason = ec.message();
      fs::remove(temp, ec);
      throw Error(to.string() + ": cannot copy " + from.string() + " there (" + reason + ")");
    }
  }
  rename_into_place(temp, to.string());
}

// Every part's outputs (BVH, and the report when there is one) into out_dir, so the merged
// folder holds the whole batch like one run's; each clip's output then names its copy there.
void gather_outputs(std::vector<BatchClipResult>& clips, const std::map<std::string, std::string>& owner,
                    const fs::path& out_dir) {
  for (BatchClipResult& c : clips) {
    if (c.output.empty()) continue;
    const fs::path name = fs::path(c.output).filename();
    const fs::path from = fs::path(owner.at(c.test_stem)) / name;
    std::error_code ec;
    if (!fs::is_regular_file(from, ec))
      throw Error("batch --merge: " + from.string() + " is missing (its part's summary lists it for clip '" +
                  c.test_stem + "')");
    place_file(from, out_dir / name);
    const fs::path report = fs::path(from).replace_extension(".json");
    if (fs::is_regular_file(report, ec)) place_file(report, out_dir / report.filename());
    c.output = (out_dir / name).string();
  }
}

}  // namespace

BatchSummary batch_merge(const std::vector<std::string>& part_dirs, const std::string& out_dir,
                         std::ostream& progress_stream) {
  if (part_dirs.empty()) throw Error("batch --merge: no part folder given");
  if (out_dir.empty()) throw Error("batch --merge: no output folder given (-o OUTDIR)");
  std::vector<Part> parts;
  for (const std::string& d : part_dirs) {
    const fs::path file = fs::path(d) / "summary.json";
    std::error_code ec;
    if (!fs::exists(file, ec))
      throw Error("batch --merge: " + d + " has no summary.json (not a finished 'gmg batch --shard K/N' folder)");
    parts.push_back({d, read_summary_file(file)});
  }
  check_parts(parts);

  BatchSummary merged;
  const BatchSummary& first = parts.front().record.summary;
  merged.seed = first.seed;
  merged.batch_clips = first.batch_clips;
  std::map<std::string, std::string> owner;  // test stem -> part folder
  for (const Part& p : parts) {
    const BatchSummary& s = p.record.summary;
    for (const BatchClipResult& c : s.clips) {
      const auto [it, inserted] = owner.emplace(c.test_stem, p.dir);
      if (!inserted)
        throw Error("batch --merge: test clip '" + c.test_stem + "' is in two parts: " + it->second + " and " + p.dir);
      merged.clips.push_back(c);
    }
    add_references(merged, s);
    merged.jobs = std::max(merged.jobs, s.jobs);
    merged.seconds = std::max(merged.seconds, s.seconds);  // parts run side by side
    merged.graph_seconds += s.graph_seconds;
    merged.interrupted = merged.interrupted || s.interrupted;
    merged.parts.push_back(p.dir);
  }
  std::sort(merged.clips.begin(), merged.clips.end(),
            [](const BatchClipResult& a, const BatchClipResult& b) { return a.test_stem < b.test_stem; });
  std::sort(merged.references.begin(), merged.references.end(),
            [](const BatchReferenceResult& a, const BatchReferenceResult& b) { return a.stem < b.stem; });
  if (static_cast<int>(merged.clips.size()) != merged.batch_clips)
    throw Error("batch --merge: the parts hold " + std::to_string(merged.clips.size()) + " test clips, the batch " +
                std::to_string(merged.batch_clips));
  count_statuses(merged);

  check_output_folder({"-o", out_dir});
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir, ec))
    throw Error(out_dir + ": cannot create the output folder (" +
                (ec ? ec.message() : std::string("a file of that name is in the way")) + ")");
  gather_outputs(merged.clips, owner, out_dir);
  BatchOptions options;
  options.blacklist = parts.front().record.blacklist;
  const BatchPairing pairing =
      enum_from_name(kBatchPairingNames, parts.front().record.pairing).value_or(BatchPairing::Random);
  write_pairs_csv(out_dir, merged.clips);
  write_summary_files(out_dir, merged, options, pairing);
  Progress progress(progress_stream, BatchProgress::Lines);
  progress.line("batch: merged " + std::to_string(parts.size()) + " parts");
  progress.line(summary_line(merged, out_dir));
  return merged;
}

}  // namespace gmg
