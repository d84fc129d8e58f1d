// Parts of a batch (--shard K/N) and joining their summaries (--merge), see batch.h "Shards".
#include <algorithm>
#include <map>

#include "engine/batch/batch_internal.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/interrupt.h"
#include "engine/core/json.h"
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
  nlohmann::json run_record;  // its batch.json; null when it has none
};

std::string part_name(const BatchShard& s) { return std::to_string(s.index) + "/" + std::to_string(s.count); }

// "P/p2 (part 2/2)"
std::string part_label(const Part& p) {
  return p.dir + (p.record.summary.shard ? " (part " + part_name(*p.record.summary.shard) + ")" : std::string());
}

// The path with symbolic links and "." and ".." resolved as far as it exists, to compare folders.
fs::path resolved(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal() : p;
}

// True when `inner` lies inside `outer` (not the same folder), both resolved.
bool lies_inside(const fs::path& inner, const fs::path& outer) {
  std::vector<fs::path> a, b;
  for (const fs::path& name : inner)
    if (!name.empty()) a.push_back(name);  // a trailing separator is an empty name
  for (const fs::path& name : outer)
    if (!name.empty()) b.push_back(name);
  return a.size() > b.size() && std::equal(b.begin(), b.end(), a.begin());
}

// The output folder is none of the parts, holds none and lies in none: a merge into a part would
// overwrite its summary with the whole batch's and mix the batch's outputs into its folder.
void check_output_apart_from_parts(const std::vector<std::string>& part_dirs, const std::string& out_dir) {
  const fs::path out = resolved(out_dir);
  for (const std::string& d : part_dirs) {
    const fs::path part = resolved(d);
    std::error_code ec;
    std::string problem;
    if (out == part || fs::equivalent(out, part, ec))
      problem = "is the part folder " + d;
    else if (lies_inside(part, out))
      problem = "holds the part folder " + d;
    else if (lies_inside(out, part))
      problem = "lies inside the part folder " + d;
    if (!problem.empty())
      throw Error("batch --merge: -o " + out_dir + " " + problem +
                  "; the merged batch goes into a folder of its own (choose another -o)");
  }
}

// What a part's clips were reenacted from, in words: "the graph g.gmg" or "a pool of 3 reference
// clips".
std::string setup_of(const BatchSummary& s) {
  if (s.references.size() == 1 && s.references.front().audio.empty()) return "the graph " + s.references.front().motion;
  return "a pool of " + std::to_string(s.references.size()) + " reference clip" + (s.references.size() == 1 ? "" : "s");
}

// Why `p` is not from the same setup as `first` (their references, or what their batch.json
// records); "" when nothing says so.
std::string setup_difference(const Part& first, const Part& p) {
  const std::vector<BatchReferenceResult>& a = first.record.summary.references;
  const std::vector<BatchReferenceResult>& b = p.record.summary.references;
  const std::string setup_a = setup_of(first.record.summary), setup_b = setup_of(p.record.summary);
  if (setup_a != setup_b) return "was made with " + setup_b + ", " + part_label(first) + " with " + setup_a;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].stem != b[i].stem || a[i].motion != b[i].motion || a[i].audio != b[i].audio ||
        a[i].transcript != b[i].transcript)
      return "has reference '" + b[i].stem + "' from " + b[i].motion + ", " + part_label(first) + " reference '" +
             a[i].stem + "' from " + a[i].motion;
  if (first.run_record.is_null() || p.run_record.is_null()) return "";
  const std::string difference = record_difference(p.run_record, first.run_record);
  return difference.empty() ? "" : "was made with " + difference + " as " + part_label(first) + " was (batch.json)";
}

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
    const std::string what = part_label(p);
    if (s.shard->count != count || s.seed != first.record.summary.seed || p.record.pairing != first.record.pairing ||
        s.batch_clips != first.record.summary.batch_clips)
      throw Error("batch --merge: " + what + " is not from the same batch as " + part_label(first) +
                  ": parts must share N, seed, pairing and clips");
    const std::string difference = setup_difference(first, p);
    if (!difference.empty())
      throw Error("batch --merge: " + what + " " + difference +
                  ": parts of one batch share its references and parameters");
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

// `from` at `to`, staged in `outputs` (in place at its commit, whole): a hard link when both are on
// one file system (no copy of hours of motion), else a copy; an existing `to` is replaced. Nothing
// when they are one file.
void place_file(const fs::path& from, const fs::path& to, OutputTransaction& outputs) {
  std::error_code ec;
  if (fs::exists(to, ec) && fs::equivalent(from, to, ec)) return;
  const std::string temp = temporary_name_for(to.string());
  const int slot = register_temporary_file(temp);  // an interrupt removes it
  fs::create_hard_link(from, temp, ec);
  if (ec) {
    ec.clear();
    fs::copy_file(from, temp, ec);
    if (ec) {
      const std::string reason = ec.message();
      fs::remove(temp, ec);
      unregister_temporary_file(slot);
      throw Error(to.string() + ": cannot copy " + from.string() + " there (" + reason + ")");
    }
  }
  outputs.stage(temp, to.string(), slot);
}

// The BVH of each clip with an output, in its part's folder; an error naming the first that is
// missing, before anything is written.
std::vector<fs::path> part_outputs(const std::vector<BatchClipResult>& clips,
                                   const std::map<std::string, std::string>& owner) {
  std::vector<fs::path> from(clips.size());
  for (std::size_t i = 0; i < clips.size(); ++i) {
    const BatchClipResult& c = clips[i];
    if (c.output.empty()) continue;
    from[i] = fs::path(owner.at(c.test_stem)) / fs::path(c.output).filename();
    std::error_code ec;
    if (!fs::is_regular_file(from[i], ec))
      throw Error("batch --merge: " + from[i].string() + " is missing (its part's summary lists it for clip '" +
                  c.test_stem + "')");
  }
  return from;
}

// Every part's outputs (BVH, and the report when there is one) into out_dir, so the merged
// folder holds the whole batch like one run's; each clip's output then names its copy there.
void gather_outputs(std::vector<BatchClipResult>& clips, const std::vector<fs::path>& from, const fs::path& out_dir,
                    OutputTransaction& outputs) {
  for (std::size_t i = 0; i < clips.size(); ++i) {
    if (from[i].empty()) continue;
    const fs::path name = from[i].filename();
    place_file(from[i], out_dir / name, outputs);
    std::error_code ec;
    const fs::path report = fs::path(from[i]).replace_extension(".json");
    if (fs::is_regular_file(report, ec)) place_file(report, out_dir / report.filename(), outputs);
    clips[i].output = (out_dir / name).string();
  }
}

}  // namespace

BatchSummary batch_merge(const std::vector<std::string>& part_dirs, const std::string& out_dir,
                         std::ostream& progress_stream) {
  if (part_dirs.empty()) throw Error("batch --merge: no part folder given");
  if (out_dir.empty()) throw Error("batch --merge: no output folder given (-o OUTDIR)");
  check_output_apart_from_parts(part_dirs, out_dir);
  std::vector<Part> parts;
  for (const std::string& d : part_dirs) {
    const fs::path file = fs::path(d) / "summary.json";
    std::error_code ec;
    if (!fs::exists(file, ec))
      throw Error("batch --merge: " + d + " has no summary.json (not a finished 'gmg batch --shard K/N' folder)");
    nlohmann::json record;  // batch.json: the settings; a part without one is compared by its summary only
    if (fs::exists(fs::path(d) / "batch.json", ec)) record = read_json_file((fs::path(d) / "batch.json").string());
    parts.push_back({d, read_summary_file(file), std::move(record)});
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
  const std::vector<fs::path> from = part_outputs(merged.clips, owner);

  // Everything is checked: the merged folder appears whole, or nothing of it (a failed copy, a
  // full disk) does.
  check_output_folder({"-o", out_dir});
  CreatedFolders folder(out_dir);
  {
    OutputTransaction outputs;
    gather_outputs(merged.clips, from, out_dir, outputs);
    BatchOptions options;
    options.blacklist = parts.front().record.blacklist;
    const BatchPairing pairing =
        enum_from_name(kBatchPairingNames, parts.front().record.pairing).value_or(BatchPairing::Random);
    write_pairs_csv(out_dir, merged.clips);
    write_summary_files(out_dir, merged, options, pairing);
    outputs.commit();
  }
  folder.keep();
  Progress progress(progress_stream, BatchProgress::Lines);
  progress.line("batch: merged " + std::to_string(parts.size()) + " parts");
  progress.line(summary_line(merged, out_dir));
  return merged;
}

}  // namespace gmg
