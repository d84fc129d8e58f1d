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

// One column of the table: its CSV name, its Markdown head (nullptr: CSV only), which Markdown
// table shows it, and how to print it.
enum class Table { Naturalness, SyncAndBehaviour, CsvOnly };

struct Column {
  const char* csv;
  const char* head;
  Table table;
  const char* format;  // printf format of one value (mean and sd use it)
  std::function<double(const AblationScore&)> get;
};

const std::vector<Column>& columns() {
  using S = const AblationScore&;
  static const std::vector<Column> c = {
      {"syn", "Syn cm/s ↓", Table::Naturalness, "%.1f", [](S s) { return s.syn; }},
      {"bc", "BC", Table::CsvOnly, "%.3f", [](S s) { return s.sync.bc; }},
      {"bc_lift", "BC lift", Table::CsvOnly, "%+.3f", [](S s) { return s.sync.bc_lift; }},
      {"div", "Div", Table::Naturalness, "%.3f", [](S s) { return s.div; }},
      {"jerk_ratio", "jerk ×", Table::Naturalness, "%.2f", [](S s) { return s.jerk_ratio; }},
      {"acc_ratio", "acc ×", Table::Naturalness, "%.2f", [](S s) { return s.acc_ratio; }},
      {"hellinger", "Hellinger", Table::Naturalness, "%.3f", [](S s) { return s.hellinger; }},
      {"hellinger_wrists", "Hell. wrists", Table::Naturalness, "%.3f", [](S s) { return s.hellinger_wrists; }},
      {"root_speed_ratio", "root speed ×", Table::Naturalness, "%.2f", [](S s) { return s.root_speed_ratio; }},
      {"jump_ratio", "jump ×", Table::Naturalness, "%.2f", [](S s) { return s.jump_ratio; }},
      {"transitions_per_s", "trans/s", Table::Naturalness, "%.2f", [](S s) { return s.transitions_per_s; }},
      {"failures", "#fail", Table::Naturalness, "%.1f", [](S s) { return static_cast<double>(s.failures); }},
      {"step_share", "steps > p99.9", Table::Naturalness, "%.4f", [](S s) { return s.step_share; }},
      {"bc_shift_lift", "BC shift lift", Table::CsvOnly, "%+.3f", [](S s) { return s.sync.bc_shift_lift; }},
      {"bc_shifted_sd", "BC shifted sd", Table::CsvOnly, "%.3f", [](S s) { return s.sync.bc_shifted_sd; }},
      {"speech_corr", "onset corr", Table::CsvOnly, "%.3f", [](S s) { return s.sync.speech_corr; }},
      {"speech_corr_lift", "onset corr lift", Table::CsvOnly, "%+.3f", [](S s) { return s.sync.speech_corr_lift; }},
      {"speech_corr_shift_lift", "onset corr shift lift", Table::CsvOnly, "%+.3f",
       [](S s) { return s.sync.speech_corr_shift_lift; }},
      {"speech_corr_shifted_sd", "onset corr shifted sd", Table::CsvOnly, "%.3f",
       [](S s) { return s.sync.speech_corr_shifted_sd; }},
      {"energy_corr", "energy corr", Table::SyncAndBehaviour, "%.3f", [](S s) { return s.sync.energy_corr; }},
      {"energy_corr_lift", "corr lift", Table::SyncAndBehaviour, "%+.3f", [](S s) { return s.sync.energy_corr_lift; }},
      {"energy_corr_mismatched_sd", "corr mismatched sd", Table::CsvOnly, "%.3f",
       [](S s) { return s.sync.energy_corr_mismatched_sd; }},
      {"beat_bc", "beat BC", Table::SyncAndBehaviour, "%.3f", [](S s) { return s.sync.beat_bc; }},
      {"beat_bc_lift", "beat BC lift", Table::SyncAndBehaviour, "%+.3f", [](S s) { return s.sync.beat_bc_lift; }},
      {"beat_bc_mismatched_sd", "beat BC mismatched sd", Table::CsvOnly, "%.3f",
       [](S s) { return s.sync.beat_bc_mismatched_sd; }},
      {"foot_slide", "foot slide", Table::SyncAndBehaviour, "%.3f", [](S s) { return s.behaviour.foot_slide; }},
      {"still_longest_s", "still run s", Table::SyncAndBehaviour, "%.2f",
       [](S s) { return s.behaviour.still_longest_s; }},
      {"still_share", "still", Table::SyncAndBehaviour, "%.3f", [](S s) { return s.behaviour.still_share; }},
      {"max_plays_per_min", "plays/min", Table::SyncAndBehaviour, "%.1f", [](S s) { return s.max_plays_per_min; }},
      {"coverage", "coverage", Table::SyncAndBehaviour, "%.2f", [](S s) { return s.coverage; }},
      {"seed_distance", "seed dist", Table::SyncAndBehaviour, "%.2f", [](S s) { return s.seed_distance; }},
  };
  return c;
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

std::string sd_format_of(const char* fmt) {
  std::string f = fmt;  // a spread has no sign
  if (f.size() > 1 && f[1] == '+') f.erase(1, 1);
  return f;
}

std::string markdown_table(const AblationResult& result, Table table) {
  std::string out = "| setup |";
  std::string rule = "| --- |";
  for (const Column& c : columns())
    if (c.table == table) {
      out += std::string(" ") + c.head + " |";
      rule += " --- |";
    }
  out += "\n" + rule + "\n";
  for (const AblationRow& row : result.rows) {
    out += std::string("| ") + enum_name(kAblationSetupNames, row.setup) + " |";
    for (const Column& c : columns()) {
      if (c.table != table) continue;
      const MeanSd m = column_stats(row, c);
      out += " " + format(c.format, m.mean) + " ± " + format(sd_format_of(c.format).c_str(), m.sd) + " |";
    }
    out += "\n";
  }
  return out;
}

}  // namespace

std::string ablation_markdown(const AblationResult& result) {
  std::string out = markdown_table(result, Table::Naturalness) + "\n" + markdown_table(result, Table::SyncAndBehaviour);
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
  out +=
      "Sync: lift = aligned − mean over the other folds' speech (mismatched speech); corr is the upper body's "
      "speed against the speech's loudness, beat BC the kinematic beat consistency (EMAGE's rule). Seed dist is "
      "the nearest two seeds' outputs, over the reference's pose variation.\n";
  // The truth, fold by fold, and the full system beside it.
  out +=
      "\n| fold | truth corr lift | full corr lift | truth beat BC lift | full beat BC lift | full jerk × | "
      "full acc × | truth foot slide | truth still run s | truth still |\n| --- | --- | --- | --- | --- | --- | "
      "--- | --- | --- | --- |\n";
  double log_jerk = 0.0, log_acc = 0.0;
  for (std::size_t f = 0; f < result.truth.size(); ++f) {
    const TruthSync& t = result.truth[f];
    std::vector<double> corr, beat, jerk, acc;
    if (full)
      for (int k = 0; k < result.seeds; ++k) {
        const AblationScore& s = full->scores[f * static_cast<std::size_t>(result.seeds) + static_cast<std::size_t>(k)];
        corr.push_back(s.sync.energy_corr_lift);
        beat.push_back(s.sync.beat_bc_lift);
        jerk.push_back(s.jerk_ratio);
        acc.push_back(s.acc_ratio);
      }
    log_jerk += std::log(std::max(1e-12, mean_sd(jerk).mean));
    log_acc += std::log(std::max(1e-12, mean_sd(acc).mean));
    out += "| " + std::to_string(f + 1) + " | " + format("%+.3f", t.sync.energy_corr_lift) + " | " +
           format("%+.3f", mean_sd(corr).mean) + " | " + format("%+.3f", t.sync.beat_bc_lift) + " | " +
           format("%+.3f", mean_sd(beat).mean) + " | " + format("%.2f", mean_sd(jerk).mean) + " | " +
           format("%.2f", mean_sd(acc).mean) + " | " + format("%.3f", t.behaviour.foot_slide) + " | " +
           format("%.2f", t.behaviour.still_longest_s) + " | " + format("%.3f", t.behaviour.still_share) + " |\n";
  }
  std::vector<double> corr, beat, bc, slide, run, still;
  for (const TruthSync& t : result.truth) {
    corr.push_back(t.sync.energy_corr_lift);
    beat.push_back(t.sync.beat_bc_lift);
    bc.push_back(t.sync.bc_lift);
    slide.push_back(t.behaviour.foot_slide);
    run.push_back(t.behaviour.still_longest_s);
    still.push_back(t.behaviour.still_share);
  }
  const double n = std::max<std::size_t>(1, result.truth.size());
  out += "\nThe truth itself: corr lift " + format("%+.3f", mean_sd(corr).mean) + " ± " +
         format("%.3f", mean_sd(corr).sd) + ", beat BC lift " + format("%+.3f", mean_sd(beat).mean) + " ± " +
         format("%.3f", mean_sd(beat).sd) + ", BC lift " + format("%+.3f", mean_sd(bc).mean) + "; foot slide " +
         format("%.3f", mean_sd(slide).mean) + ", longest still run " + format("%.2f", mean_sd(run).mean) +
         " s, still " + format("%.3f", mean_sd(still).mean) + ". Full system, geometric mean over folds: jerk × " +
         format("%.2f", std::exp(log_jerk / n)) + ", acc × " + format("%.2f", std::exp(log_acc / n)) + ".\n";
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
