// The ablation table as Markdown and CSV.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iterator>
#include <numeric>

#include "engine/ablation/ablation.h"

namespace gmg {
namespace {

struct MeanSd {
  double mean = 0, sd = 0;
};

// Over the defined values (a NaN is a metric undefined for that motion); NaN when none is.
MeanSd mean_sd(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  MeanSd r;
  if (v.empty()) return {std::nan(""), std::nan("")};
  r.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - r.mean) * (x - r.mean);
  r.sd = v.size() > 1 ? std::sqrt(ss / static_cast<double>(v.size() - 1)) : 0.0;
  return r;
}

// One column of the table: its CSV name, its Markdown head (nullptr: CSV only), which Markdown
// table shows it, and how to print it.
enum class Table { Naturalness, SyncAndBehaviour, Lifelike, CsvOnly };

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
      {"coverage", "coverage", Table::SyncAndBehaviour, "%.2f", [](S s) { return s.coverage; }},
      {"seed_distance", "seed dist", Table::SyncAndBehaviour, "%.2f", [](S s) { return s.seed_distance; }},
      {"knee_share_ratio", "knee share ×", Table::Lifelike, "%.2f", [](S s) { return s.lifelike.knee_share_ratio; }},
      {"knee_p90_deg", "knee p90 °", Table::CsvOnly, "%.1f", [](S s) { return s.lifelike.knee_p90_deg; }},
      {"body_jerk_ratio", "body jerk ×", Table::Lifelike, "%.2f", [](S s) { return s.lifelike.body_jerk_ratio; }},
      {"body_jerk_p99_ratio", "jerk p99 ×", Table::Lifelike, "%.2f",
       [](S s) { return s.lifelike.body_jerk_p99_ratio; }},
      {"still_longest_ratio", "still run ×", Table::Lifelike, "%.2f",
       [](S s) { return s.lifelike.still_longest_ratio; }},
      {"still_longest_s", "still run s", Table::CsvOnly, "%.2f", [](S s) { return s.lifelike.still_longest_s; }},
      {"foot_slide_ratio", "foot slide ×", Table::Lifelike, "%.2f", [](S s) { return s.lifelike.foot_slide_ratio; }},
      {"foot_slide_share", "foot slide", Table::CsvOnly, "%.3f", [](S s) { return s.lifelike.foot_slide_share; }},
      {"junctions_per_min", "junctions/min", Table::Lifelike, "%.1f", [](S s) { return s.paths.junctions_per_min; }},
      {"junction_gap_median_cm", "gap cm", Table::Lifelike, "%.1f", [](S s) { return s.paths.junction_gap_median_cm; }},
      {"stance_changes_per_min", "stance/min", Table::Lifelike, "%.1f",
       [](S s) { return s.paths.stance_changes_per_min; }},
      {"max_plays_upper", "plays up", Table::Lifelike, "%.1f",
       [](S s) { return static_cast<double>(s.paths.max_plays_upper); }},
      {"max_plays_lower", "plays low", Table::Lifelike, "%.1f",
       [](S s) { return static_cast<double>(s.paths.max_plays_lower); }},
      {"back_jumps_upper", "back-jumps up", Table::Lifelike, "%.1f",
       [](S s) { return static_cast<double>(s.paths.back_jumps_upper); }},
      {"back_jumps_lower", "back-jumps low", Table::Lifelike, "%.1f",
       [](S s) { return static_cast<double>(s.paths.back_jumps_lower); }},
  };
  return c;
}

MeanSd column_stats(const AblationRow& row, const Column& col) {
  std::vector<double> v;
  for (const AblationScore& s : row.scores) v.push_back(col.get(s));
  return mean_sd(v);
}

// An undefined value (NaN: no motion had it) prints as "–" in Markdown.
std::string format(const char* fmt, double v) {
  if (std::isnan(v)) return "–";
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
  std::string out = markdown_table(result, Table::Naturalness) + "\n" +
                    markdown_table(result, Table::SyncAndBehaviour) + "\n" + markdown_table(result, Table::Lifelike);
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
      "the nearest two seeds' outputs, over the reference's pose variation.\n"
      "Lifelike: ratios (×) to the fold's reference part (knee share above its 90th-percentile knee bend, body "
      "jerk and its 99th percentile, longest still run, foot slide; – where undefined); junctions, gaps and "
      "stance changes of the paths; plays and back-jumps of the upper body and the lower body.\n";
  // The truth, fold by fold, and the full system beside it: sync lifts, smoothness, lifelike ratios.
  using Get = std::function<double(const SyncScores&, const LifelikeMotion&)>;
  struct FoldColumn {
    const char* head;
    const char* format;
    Get get;
  };
  const FoldColumn fold_columns[] = {
      {"corr lift", "%+.3f", [](const SyncScores& s, const LifelikeMotion&) { return s.energy_corr_lift; }},
      {"beat BC lift", "%+.3f", [](const SyncScores& s, const LifelikeMotion&) { return s.beat_bc_lift; }},
      {"knee share ×", "%.2f", [](const SyncScores&, const LifelikeMotion& l) { return l.knee_share_ratio; }},
      {"jerk p99 ×", "%.2f", [](const SyncScores&, const LifelikeMotion& l) { return l.body_jerk_p99_ratio; }},
      {"still run ×", "%.2f", [](const SyncScores&, const LifelikeMotion& l) { return l.still_longest_ratio; }},
      {"foot slide ×", "%.2f", [](const SyncScores&, const LifelikeMotion& l) { return l.foot_slide_ratio; }}};
  out += "\n| fold |";
  for (const FoldColumn& c : fold_columns) out += std::string(" truth ") + c.head + " | full " + c.head + " |";
  out += " full jerk × | full acc × |\n| --- |";
  for (std::size_t i = 0; i < 2 * std::size(fold_columns) + 2; ++i) out += " --- |";
  out += "\n";
  double log_jerk = 0.0, log_acc = 0.0;
  for (std::size_t f = 0; f < result.truth.size(); ++f) {
    const TruthSync& t = result.truth[f];
    std::vector<const AblationScore*> seeds;
    if (full)
      for (int k = 0; k < result.seeds; ++k)
        seeds.push_back(&full->scores[f * static_cast<std::size_t>(result.seeds) + static_cast<std::size_t>(k)]);
    auto full_mean = [&](const std::function<double(const AblationScore&)>& get) {
      std::vector<double> v;
      for (const AblationScore* s : seeds) v.push_back(get(*s));
      return mean_sd(v).mean;
    };
    out += "| " + std::to_string(f + 1) + " |";
    for (const FoldColumn& c : fold_columns)
      out += " " + format(c.format, c.get(t.sync, t.lifelike)) + " | " +
             format(c.format, full_mean([&](const AblationScore& s) { return c.get(s.sync, s.lifelike); })) + " |";
    const double jerk = full_mean([](const AblationScore& s) { return s.jerk_ratio; });
    const double acc = full_mean([](const AblationScore& s) { return s.acc_ratio; });
    out += " " + format("%.2f", jerk) + " | " + format("%.2f", acc) + " |\n";
    log_jerk += std::log(std::max(1e-12, jerk));
    log_acc += std::log(std::max(1e-12, acc));
  }
  auto truth_mean = [&](const Get& get) {
    std::vector<double> v;
    for (const TruthSync& t : result.truth) v.push_back(get(t.sync, t.lifelike));
    return mean_sd(v);
  };
  const MeanSd corr = truth_mean(fold_columns[0].get), beat = truth_mean(fold_columns[1].get);
  const double n = std::max<std::size_t>(1, result.truth.size());
  out += "\nThe truth itself: corr lift " + format("%+.3f", corr.mean) + " ± " + format("%.3f", corr.sd) +
         ", beat BC lift " + format("%+.3f", beat.mean) + " ± " + format("%.3f", beat.sd) + ", BC lift " +
         format("%+.3f", truth_mean([](const SyncScores& s, const LifelikeMotion&) { return s.bc_lift; }).mean) +
         "; against the reference part: knee share × " + format("%.2f", truth_mean(fold_columns[2].get).mean) +
         ", jerk p99 × " + format("%.2f", truth_mean(fold_columns[3].get).mean) + ", still run × " +
         format("%.2f", truth_mean(fold_columns[4].get).mean) + ", foot slide × " +
         format("%.2f", truth_mean(fold_columns[5].get).mean) + ". Full system, geometric mean over folds: jerk × " +
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
      // An undefined value is "nan", as numpy and pandas read it.
      out += "," + (std::isnan(m.mean) ? std::string("nan") : format("%.6g", m.mean)) + "," +
             (std::isnan(m.sd) ? std::string("nan") : format("%.6g", m.sd));
    }
    out += "\n";
  }
  return out;
}

}  // namespace gmg
