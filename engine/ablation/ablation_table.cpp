// The ablation table as Markdown and CSV.
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>

#include "engine/ablation/ablation.h"

namespace gmg {
namespace {

struct MeanSd {
  double mean = 0, sd = 0;
};

MeanSd mean_sd(const std::vector<double>& v) {
  MeanSd r;
  if (v.empty()) return r;
  r.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - r.mean) * (x - r.mean);
  r.sd = v.size() > 1 ? std::sqrt(ss / static_cast<double>(v.size() - 1)) : 0.0;
  return r;
}

// One column of the table: its CSV name, its Markdown head and how to print it.
struct Column {
  const char* csv;
  const char* head;
  const char* format;  // printf format of one value (mean and sd use it)
  std::function<double(const AblationScore&)> get;
};

const std::vector<Column>& columns() {
  static const std::vector<Column> c = {
      {"syn", "Syn cm/s ↓", "%.1f", [](const AblationScore& s) { return s.syn; }},
      {"bc", "BC", "%.3f", [](const AblationScore& s) { return s.bc; }},
      {"bc_lift", "BC lift", "%+.3f", [](const AblationScore& s) { return s.bc_lift; }},
      {"div", "Div", "%.3f", [](const AblationScore& s) { return s.div; }},
      {"jerk_ratio", "jerk ×", "%.2f", [](const AblationScore& s) { return s.jerk_ratio; }},
      {"acc_ratio", "acc ×", "%.2f", [](const AblationScore& s) { return s.acc_ratio; }},
      {"hellinger", "Hellinger", "%.3f", [](const AblationScore& s) { return s.hellinger; }},
      {"hellinger_wrists", "Hell. wrists", "%.3f", [](const AblationScore& s) { return s.hellinger_wrists; }},
      {"root_speed_ratio", "root speed ×", "%.2f", [](const AblationScore& s) { return s.root_speed_ratio; }},
      {"jump_ratio", "jump ×", "%.2f", [](const AblationScore& s) { return s.jump_ratio; }},
      {"transitions_per_s", "trans/s", "%.2f", [](const AblationScore& s) { return s.transitions_per_s; }},
      {"failures", "#fail", "%.1f", [](const AblationScore& s) { return static_cast<double>(s.failures); }},
      // Beyond the required columns, in the same form.
      {"step_share", "steps > p99.9", "%.4f", [](const AblationScore& s) { return s.step_share; }},
      {"bc_shifted_sd", "BC shifted sd", "%.3f", [](const AblationScore& s) { return s.bc_shifted_sd; }},
      {"speech_corr", "corr", "%.3f", [](const AblationScore& s) { return s.speech_corr; }},
      {"speech_corr_lift", "corr lift", "%+.3f", [](const AblationScore& s) { return s.speech_corr_lift; }},
      {"speech_corr_shifted_sd", "corr shifted sd", "%.3f",
       [](const AblationScore& s) { return s.speech_corr_shifted_sd; }},
  };
  return c;
}

const Column& column(const std::string& name) {
  for (const Column& c : columns())
    if (name == c.csv) return c;
  return columns().front();
}

MeanSd column_stats(const AblationRow& row, const Column& col) {
  std::vector<double> v;
  for (const AblationScore& s : row.scores) v.push_back(col.get(s));
  return mean_sd(v);
}

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// Markdown columns shown: everything but the two shifted spreads, which go into the notes.
bool in_markdown(const Column& c) {
  const std::string n = c.csv;
  return n != "bc_shifted_sd" && n != "speech_corr_shifted_sd";
}

}  // namespace

std::string ablation_markdown(const AblationResult& result) {
  std::string out = "| setup |";
  std::string rule = "| --- |";
  for (const Column& c : columns())
    if (in_markdown(c)) {
      out += std::string(" ") + c.head + " |";
      rule += " --- |";
    }
  out += "\n" + rule + "\n";
  for (const AblationRow& row : result.rows) {
    out += std::string("| ") + enum_name(kAblationSetupNames, row.setup) + " |";
    for (const Column& c : columns()) {
      if (!in_markdown(c)) continue;
      const MeanSd m = column_stats(row, c);
      std::string sd_format = c.format;  // a spread has no sign
      if (sd_format.size() > 1 && sd_format[1] == '+') sd_format.erase(1, 1);
      out += " " + format(c.format, m.mean) + " ± " + format(sd_format.c_str(), m.sd) + " |";
    }
    out += "\n";
  }
  // Notes: what the numbers are, and what the truth itself scores on the sync metrics.
  std::vector<double> bc, bc_lift, bc_sd, corr, corr_lift, corr_sd;
  for (const TruthSync& t : result.truth) {
    bc.push_back(t.bc);
    bc_lift.push_back(t.bc_lift);
    bc_sd.push_back(t.bc_shifted_sd);
    corr.push_back(t.speech_corr);
    corr_lift.push_back(t.speech_corr_lift);
    corr_sd.push_back(t.speech_corr_shifted_sd);
  }
  const AblationRow* full = nullptr;
  for (const AblationRow& r : result.rows)
    if (r.setup == AblationSetup::Full) full = &r;
  out += "\nMean ± sd over " + std::to_string(result.folds) + " time folds × " + std::to_string(result.seeds) +
         " seeds. Ratios (×) are to the truth of each fold (jerk, acceleration, root speed) and to the reference "
         "part's 99.9th-percentile frame step (jump); 1 is the capture's own value. Hellinger uses " +
         (result.hist_bins == HistogramBins::Genea
              ? "the GENEA bins (" + format("%g", result.hist_bin_width) + " cm/s, speeds above 49 cm/s dropped)"
              : "our bins (" + format("%g", result.hist_bin_width) + " cm/s over 0-50 cm/s plus an overflow bin)") +
         ".\n";
  out += "Sync control: lift = aligned − mean over " + std::to_string(result.control_shifts) +
         " circular shifts of the test audio; a lift within the shifted sd means the metric saw no synchrony. "
         "Shifted sd of the full system: BC " +
         (full ? format("%.3f", column_stats(*full, column("bc_shifted_sd")).mean) : std::string("-")) + ", corr " +
         (full ? format("%.3f", column_stats(*full, column("speech_corr_shifted_sd")).mean) : std::string("-")) + ".\n";
  out += "The truth itself: BC " + format("%.3f", mean_sd(bc).mean) + " (lift " +
         format("%+.3f", mean_sd(bc_lift).mean) + ", shifted sd " + format("%.3f", mean_sd(bc_sd).mean) + "), corr " +
         format("%.3f", mean_sd(corr).mean) + " (lift " + format("%+.3f", mean_sd(corr_lift).mean) + ", shifted sd " +
         format("%.3f", mean_sd(corr_sd).mean) + ").\n";
  return out;
}

std::string ablation_csv(const AblationResult& result) {
  std::string out = "setup";
  for (const Column& c : columns()) out += std::string(",") + c.csv + "," + c.csv + "_sd";
  out += "\n";
  for (const AblationRow& row : result.rows) {
    out += enum_name(kAblationSetupNames, row.setup);
    for (const Column& c : columns()) {
      const MeanSd m = column_stats(row, c);
      out += "," + format("%.6g", m.mean) + "," + format("%.6g", m.sd);
    }
    out += "\n";
  }
  return out;
}

}  // namespace gmg
