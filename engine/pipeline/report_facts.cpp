#include "engine/pipeline/report_facts.h"

#include "engine/core/error.h"
#include "engine/core/json.h"

namespace gmg {
namespace {

// The graph frames of one subsequence's path, from its [first, last] ranges.
std::vector<int> path_frames(const nlohmann::json& s, const std::string& path) {
  std::vector<int> frames;
  for (const nlohmann::json& r : s["graph_ranges"]) {
    if (!r.is_array() || r.size() != 2 || !r[0].is_number_integer() || !r[1].is_number_integer() ||
        r[1].get<long>() < r[0].get<long>() || r[1].get<long>() - r[0].get<long>() > 10000000)
      throw Error(path + ": a graph range is not [first, last]");
    for (int g = r[0].get<int>(); g <= r[1].get<int>(); ++g) frames.push_back(g);
  }
  return frames;
}

// [[first, last), ...] output frames as seconds.
std::vector<std::pair<double, double>> stretches_s(const nlohmann::json& list, double fps, const std::string& path) {
  std::vector<std::pair<double, double>> out;
  if (!list.is_array()) throw Error(path + ": the control's stretches are not a list");
  for (const nlohmann::json& r : list) {
    if (!r.is_array() || r.size() != 2 || !r[0].is_number_integer() || !r[1].is_number_integer() ||
        r[1].get<long>() < r[0].get<long>())
      throw Error(path + ": a control stretch is not [first, last)");
    out.emplace_back(r[0].get<double>() / fps, r[1].get<double>() / fps);
  }
  return out;
}

void control_facts(const nlohmann::json& c, double fps, const std::string& path, ReportFacts& f) {
  if (!c.is_object() || !c.contains("kept") || !c.contains("planned") || !c.contains("pinned") ||
      !c["pinned"].is_array())
    throw Error(path + ": its control lacks kept, planned or pinned");
  f.kept_s = stretches_s(c["kept"], fps, path);
  f.planned_s = stretches_s(c["planned"], fps, path);
  for (const nlohmann::json& p : c["pinned"]) {
    if (!p.is_object() || !p.contains("start_frame") || !p.contains("frames") ||
        !p["start_frame"].is_number_integer() || !p["frames"].is_number_integer())
      throw Error(path + ": a pin of its control lacks start_frame or frames");
    const double start = p["start_frame"].get<double>();
    f.pinned_s.emplace_back(start / fps, (start + p["frames"].get<double>()) / fps);
  }
}

}  // namespace

ReportFacts read_report_facts(const std::string& path, double fps) {
  return report_facts_of(read_json_file(path), fps, path);
}

ReportFacts report_facts_of(const nlohmann::json& rep, double fps, const std::string& path) {
  if (!rep.is_object() || !rep.contains("totals") || !rep["totals"].is_object() ||
      !rep["totals"].contains("failures") || !rep.contains("subsequences") || !rep["subsequences"].is_array())
    throw Error(path + ": not a gmg reenactment report (no totals.failures or subsequences)");
  ReportFacts f;
  f.totals = rep["totals"];
  if (rep.contains("parameters") && rep["parameters"].is_object()) f.parameters = rep["parameters"];
  if (rep.contains("frames") && rep["frames"].is_number_integer()) f.frames = rep["frames"].get<int>();
  int previous = -2;
  for (const nlohmann::json& s : rep["subsequences"]) {
    if (!s.is_object() || !s.contains("graph_ranges") || !s.contains("start_frame") || !s.contains("target_length") ||
        !s["graph_ranges"].is_array() || !s["start_frame"].is_number_integer() ||
        !s["target_length"].is_number_integer())
      throw Error(path + ": a subsequence lacks start_frame, target_length or graph_ranges");
    const int start = s["start_frame"].get<int>(), length = s["target_length"].get<int>();
    const std::vector<int> frames = path_frames(s, path);
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const int before = i == 0 ? previous : frames[i - 1];
      if (before != -2 && frames[i] != before + 1) {
        const double x = frames.size() > 1 ? static_cast<double>(i) * (length - 1) / (frames.size() - 1) : 0.0;
        f.junctions_s.push_back((start + x) / fps);
      }
    }
    if (!frames.empty()) previous = frames.back();
    f.source_frames.insert(f.source_frames.end(), frames.begin(), frames.end());
  }
  if (rep.contains("control")) control_facts(rep["control"], fps, path, f);
  return f;
}

}  // namespace gmg
