// The records of a batch run: OUTDIR/summary.csv and OUTDIR/summary.json, and what a resumed
// run takes over from the previous summary.json.
#include <iomanip>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/batch/batch_internal.h"
#include "engine/core/csv.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/json.h"

namespace gmg::batch {
namespace {

using ojson = nlohmann::ordered_json;

// null for "" (no reference, no output, no error), else the text.
ojson text_or_null(const std::string& s) { return s.empty() ? ojson(nullptr) : ojson(s); }

ojson reference_json(const BatchReferenceResult& r) {
  return {{"stem", r.stem},
          {"motion", r.motion},
          {"audio", r.audio},
          {"transcript", text_or_null(r.transcript)},
          {"clips", r.clips},
          {"frames", r.frames},
          {"build_seconds", r.build_seconds},
          {"error", text_or_null(r.error)}};
}

ojson clip_json(const BatchClipResult& c) {
  return {{"test", c.test_stem},
          {"reference", text_or_null(c.reference_stem)},
          {"status", enum_name(kBatchClipStatusNames, c.status)},
          {"frames", c.frames},
          {"fallbacks", c.fallbacks},
          {"failures", c.failures},
          {"seconds", c.seconds},
          {"output", text_or_null(c.output)},
          {"error", text_or_null(c.error)}};
}

ojson summary_json(const BatchSummary& s, const BatchOptions& o, BatchPairing pairing) {
  ojson j;
  j["tool"] = "gmg batch";
  j["seed"] = s.seed;
  j["pairing"] = enum_name(kBatchPairingNames, pairing);
  j["blacklist"] = text_or_null(o.blacklist);
  j["jobs"] = s.jobs;
  j["interrupted"] = s.interrupted;
  if (s.shard) j["shard"] = {{"index", s.shard->index}, {"count", s.shard->count}, {"batch_clips", s.batch_clips}};
  if (!s.parts.empty()) j["parts"] = s.parts;
  j["counts"] = {{"clips", s.clips.size()},     {"ok", s.ok},
                 {"failed", s.failed},          {"skipped", s.skipped},
                 {"cancelled", s.cancelled},    {"references", s.references.size()},
                 {"blacklisted", s.blacklisted}};
  j["seconds"] = s.seconds;
  j["graph_seconds"] = s.graph_seconds;
  j["notes"] = s.notes;
  ojson refs = ojson::array();
  for (const BatchReferenceResult& r : s.references) refs.push_back(reference_json(r));
  j["references"] = refs;
  ojson clips = ojson::array();
  for (const BatchClipResult& c : s.clips) clips.push_back(clip_json(c));
  j["clips"] = clips;
  return j;
}

// One clip of a summary.json; a field of the wrong type reads as absent (0 or "").
PreviousClip previous_clip(const nlohmann::json& p) {
  const auto text = [&](const char* k) {
    return p.contains(k) && p[k].is_string() ? p[k].get<std::string>() : std::string();
  };
  const auto number = [&](const char* k) { return p.contains(k) && p[k].is_number() ? p[k].get<double>() : 0.0; };
  PreviousClip c;
  c.status = enum_from_name(kBatchClipStatusNames, text("status"));
  c.reference = text("reference");
  c.frames = number("frames");
  c.fallbacks = number("fallbacks");
  c.failures = number("failures");
  c.seconds = number("seconds");
  return c;
}

// A field of a summary.json, or `fallback` when absent or of another type.
template <typename T>
T field(const nlohmann::json& j, const char* key, T fallback) {
  if (!j.is_object() || !j.contains(key)) return fallback;
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    return fallback;
  }
}

std::string text_field(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j.at(key).is_string() ? j.at(key).get<std::string>() : std::string();
}

}  // namespace

RecordedSummary read_summary_file(const fs::path& path) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_file_bytes(path.string()));
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string() + ": not a batch summary (" + e.what() + ")");
  }
  if (!j.is_object() || field<std::string>(j, "tool", "") != "gmg batch" || !j.contains("clips") ||
      !j.at("clips").is_array())
    throw Error(path.string() + ": not a gmg batch summary.json");
  RecordedSummary r;
  BatchSummary& s = r.summary;
  s.seed = field<std::uint64_t>(j, "seed", 0);
  s.jobs = field<int>(j, "jobs", 1);
  s.interrupted = field<bool>(j, "interrupted", false);
  s.seconds = field<double>(j, "seconds", 0.0);
  s.graph_seconds = field<double>(j, "graph_seconds", 0.0);
  r.pairing = text_field(j, "pairing");
  r.blacklist = text_field(j, "blacklist");
  if (j.contains("shard") && j.at("shard").is_object()) {
    const nlohmann::json& sh = j.at("shard");
    s.shard = BatchShard{field<int>(sh, "index", 0), field<int>(sh, "count", 0)};
    s.batch_clips = field<int>(sh, "batch_clips", -1);
  } else {
    s.batch_clips = static_cast<int>(j.at("clips").size());
  }
  for (const nlohmann::json& c : j.at("clips")) {
    BatchClipResult out;
    out.test_stem = text_field(c, "test");
    out.reference_stem = text_field(c, "reference");
    const std::optional<BatchClipStatus> status = enum_from_name(kBatchClipStatusNames, text_field(c, "status"));
    if (out.test_stem.empty() || !status) throw Error(path.string() + ": a clip without test stem or status");
    out.status = *status;
    out.frames = field<int>(c, "frames", 0);
    out.fallbacks = field<int>(c, "fallbacks", 0);
    out.failures = field<int>(c, "failures", 0);
    out.seconds = field<double>(c, "seconds", 0.0);
    out.output = text_field(c, "output");
    out.error = text_field(c, "error");
    s.clips.push_back(std::move(out));
  }
  if (j.contains("references") && j.at("references").is_array())
    for (const nlohmann::json& x : j.at("references"))
      s.references.push_back({text_field(x, "stem"), text_field(x, "motion"), text_field(x, "audio"),
                              text_field(x, "transcript"), field<int>(x, "clips", 0), field<int>(x, "frames", 0),
                              field<double>(x, "build_seconds", 0.0), text_field(x, "error")});
  return r;
}

std::string fixed(double v, int decimals) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(decimals) << v;
  return os.str();
}

std::map<std::string, PreviousClip> read_previous_summary(const fs::path& out_dir) {
  std::map<std::string, PreviousClip> out;
  std::error_code ec;
  const fs::path prev = out_dir / "summary.json";
  if (!fs::exists(prev, ec)) return out;
  try {
    const nlohmann::json j = read_json_file(prev.string());
    for (const nlohmann::json& c : j.at("clips"))
      if (c.at("test").is_string()) out[c.at("test").get<std::string>()] = previous_clip(c);
  } catch (const std::exception&) {
    // A damaged old record only loses the figures from the damage on.
  }
  return out;
}

void carry_over_previous(BatchClipResult& c, const std::map<std::string, PreviousClip>& previous) {
  const auto it = previous.find(c.test_stem);
  if (it == previous.end()) return;
  const PreviousClip& p = it->second;
  const bool made = p.status == BatchClipStatus::Ok || p.status == BatchClipStatus::Skipped;
  if (!made || p.reference != c.reference_stem) return;
  c.frames = static_cast<int>(p.frames);
  c.fallbacks = static_cast<int>(p.fallbacks);
  c.failures = static_cast<int>(p.failures);
  c.seconds = p.seconds;
}

void count_statuses(BatchSummary& summary) {
  for (BatchClipResult& c : summary.clips) {
    if (c.status == BatchClipStatus::Pending) {
      c.status = BatchClipStatus::Cancelled;
      c.output.clear();
    }
    switch (c.status) {
      case BatchClipStatus::Ok:
        ++summary.ok;
        break;
      case BatchClipStatus::Failed:
        ++summary.failed;
        break;
      case BatchClipStatus::Skipped:
        ++summary.skipped;
        break;
      default:
        ++summary.cancelled;
        break;
    }
  }
}

void write_summary_files(const fs::path& out_dir, const BatchSummary& summary, const BatchOptions& options,
                         BatchPairing pairing) {
  write_file_atomically((out_dir / "summary.csv").string(), [&](std::ostream& os) {
    os << csv_line(
        {"test_stem", "reference_stem", "status", "frames", "fallbacks", "failures", "seconds", "output", "error"});
    for (const BatchClipResult& c : summary.clips)
      os << csv_line({c.test_stem, c.reference_stem, enum_name(kBatchClipStatusNames, c.status),
                      std::to_string(c.frames), std::to_string(c.fallbacks), std::to_string(c.failures),
                      fixed(c.seconds, 3), c.output, c.error});
  });
  const std::string json = json_dump(summary_json(summary, options, pairing), 2) + "\n";
  write_file_atomically((out_dir / "summary.json").string(), [&](std::ostream& os) { os << json; });
}

std::string summary_line(const BatchSummary& summary, const fs::path& out_dir) {
  std::ostringstream os;
  os << "batch: " << summary.ok << " ok, " << summary.failed << " failed, " << summary.skipped << " skipped";
  if (summary.cancelled) os << ", " << summary.cancelled << " cancelled (interrupted)";
  os << " in " << fixed(summary.seconds, 1) << "s (graphs " << fixed(summary.graph_seconds, 1) << "s); summary in "
     << (out_dir / "summary.csv").string();
  return os.str();
}

}  // namespace gmg::batch
