// What a reenactment report (report.h) says about how its output was made, read back from the
// JSON: `gmg evaluate` uses it for failures, fallbacks, transitions and the plot's junctions,
// `gmg render` for its junction markers.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace gmg {

struct ReportFacts {
  nlohmann::json totals;            // the report's "totals" object (has "failures")
  nlohmann::json parameters;        // its "parameters" object; null when absent
  int frames = -1;                  // its "frames" (the output's frame count); -1 when absent
  std::vector<int> source_frames;   // graph frames in output order
  std::vector<double> junctions_s;  // output times (s) where the source jumps
  // The report's "control" (engine/pipeline/control.h) as [from, to) output times (s): the
  // stretches kept from an earlier output, planned afresh, and pinned; empty without one.
  std::vector<std::pair<double, double>> kept_s, planned_s, pinned_s;
};

// Reads the report at `path`; junction times are in seconds at the output's `fps`. A junction is
// where the graph frame does not follow its predecessor (inside a subsequence or across two);
// the path of a subsequence is resampled evenly onto its target frames, so path index i of n
// lands at start_frame + i * (target_length - 1) / (n - 1). gmg::Error naming the file when it
// is not a reenactment report (no totals.failures or subsequences) or a subsequence is malformed.
ReportFacts read_report_facts(const std::string& path, double fps);

// The same for a report already in memory; `name` labels errors.
ReportFacts report_facts_of(const nlohmann::json& report, double fps, const std::string& name);

}  // namespace gmg
