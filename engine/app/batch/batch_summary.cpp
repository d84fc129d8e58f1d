// The records of a batch run: OUTDIR/summary.csv and OUTDIR/summary.json, and what a resumed
// run takes over from the previous summary.json.
#include <iomanip>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/app/batch/batch_internal.h"
#include "engine/core/csv.h"
#include "engine/core/files.h"
#include "engine/core/json.h"

namespace gmg::batch_internal {
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

}  // namespace

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

}  // namespace gmg::batch_internal
