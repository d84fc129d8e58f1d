#include "engine/evaluate/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <cairo-svg.h>
#include <cairo.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "engine/metrics/naturalness.h"

namespace gmg {

std::vector<double> mean_joint_speed(const Eigen::MatrixXd& pos, double fps) {
  const Eigen::MatrixXd rel = root_relative(pos);
  const Eigen::Index joints = pos.cols() / 3;
  std::vector<double> out(static_cast<std::size_t>(pos.rows()), 0.0);
  for (Eigen::Index t = 1; t < pos.rows(); ++t) {
    double sum = 0.0;
    for (Eigen::Index j = 1; j < joints; ++j) sum += (rel.block<1, 3>(t, 3 * j) - rel.block<1, 3>(t - 1, 3 * j)).norm();
    out[static_cast<std::size_t>(t)] = sum / std::max<Eigen::Index>(1, joints - 1) * fps;
  }
  if (out.size() > 1) out[0] = out[1];
  return out;
}

PlotAxis plot_axis(double top, int max_intervals, bool cover) {
  if (!(top > 0) || !std::isfinite(top) || max_intervals < 1)
    throw Error("plot_axis: the top must be a positive number and the intervals at least 1");
  // The step: 1, 2 or 5 times a power of ten, from the one just under top / max_intervals up.
  double decade = std::pow(10.0, std::floor(std::log10(top / max_intervals)));
  PlotAxis axis;
  for (int k = 0;; k = (k + 1) % 3) {
    const double step = decade * (k == 0 ? 1.0 : (k == 1 ? 2.0 : 5.0));
    // Counted with a tolerance, so a top that is a multiple of the step (up to rounding) is one.
    const double intervals = top / step;
    const double n = cover ? std::ceil(intervals - 1e-9) : std::floor(intervals + 1e-9);
    if (n <= max_intervals) {
      axis.step = step;
      for (int i = 0; i <= static_cast<int>(n); ++i) axis.ticks.push_back(i * step);
      return axis;
    }
    if (k == 2) decade *= 10.0;
  }
}

std::string plot_tick_label(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

namespace {

constexpr double kWidth = 1600, kHeight = 720;
constexpr double kLeft = 90, kRight = 30, kTop = 70, kPanelH = 250, kGap = 60;
constexpr double kAxisHeadroom = 1.04;  // the value axes reach above the highest value
const char* const kFont = "sans-serif";

struct Rgb {
  double r, g, b;
};
constexpr Rgb kGenerated{0.12, 0.35, 0.80}, kTruth{0.45, 0.45, 0.45}, kJunction{0.85, 0.12, 0.12};
constexpr Rgb kEnvelope{0.93, 0.50, 0.05}, kOnset{0.10, 0.60, 0.20}, kInk{0.15, 0.15, 0.15};

double largest(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (double v : a) m = std::max(m, v);
  for (double v : b) m = std::max(m, v);
  return m;
}

PlotAxis value_axis(double largest_value) {
  return plot_axis(largest_value > 0 ? kAxisHeadroom * largest_value : 1.0, 5, true);
}

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void set_color(cairo_t* cr, const Rgb& c, double alpha = 1.0) { cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha); }

// Text at (x, y): align 0 left, 0.5 centred, 1 right of x; y is the baseline.
void text(cairo_t* cr, double x, double y, const std::string& s, double size, double align = 0,
          cairo_font_weight_t weight = CAIRO_FONT_WEIGHT_NORMAL) {
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, weight);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, x - align * e.x_advance, y);
  cairo_show_text(cr, s.c_str());
}

void line(cairo_t* cr, double x0, double y0, double x1, double y1) {
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
}

// The panel's grid, frame, value ticks with their labels, time ticks (labelled when
// label_time), and its axis label above its top-left corner.
void axes(cairo_t* cr, const PlotPanel& p, const PlotAxis& values, const PlotAxis& time, const std::string& label,
          bool label_time) {
  cairo_set_line_width(cr, 1.0);
  cairo_set_source_rgb(cr, 0.90, 0.90, 0.90);
  for (double v : values.ticks) line(cr, p.x0, p.y(v), p.x0 + p.w, p.y(v));
  for (double t : time.ticks) line(cr, p.x(t), p.y0, p.x(t), p.y0 + p.h);
  cairo_stroke(cr);
  set_color(cr, kInk);
  for (double v : values.ticks) line(cr, p.x0 - 6, p.y(v), p.x0, p.y(v));
  for (double t : time.ticks) line(cr, p.x(t), p.y0 + p.h, p.x(t), p.y0 + p.h + 6);
  cairo_stroke(cr);
  cairo_set_line_width(cr, 1.2);
  cairo_rectangle(cr, p.x0, p.y0, p.w, p.h);
  cairo_stroke(cr);
  for (double v : values.ticks) text(cr, p.x0 - 10, p.y(v) + 5, plot_tick_label(v, values.step), 14, 1.0);
  if (label_time)
    for (double t : time.ticks) text(cr, p.x(t), p.y0 + p.h + 24, plot_tick_label(t, time.step), 14, 0.5);
  text(cr, p.x0, p.y0 - 12, label, 16, 0, CAIRO_FONT_WEIGHT_BOLD);
}

// Only what lies inside the panel is drawn until cairo_restore.
void clip_to(cairo_t* cr, const PlotPanel& p) {
  cairo_save(cr);
  cairo_rectangle(cr, p.x0, p.y0, p.w, p.h);
  cairo_clip(cr);
}

void curve(cairo_t* cr, const PlotPanel& p, const std::vector<double>& v, double dt, const Rgb& c) {
  if (v.empty()) return;
  set_color(cr, c);
  cairo_set_line_width(cr, 1.6);
  cairo_move_to(cr, p.x(0), p.y(v[0]));
  for (std::size_t i = 1; i < v.size(); ++i) cairo_line_to(cr, p.x(static_cast<double>(i) * dt), p.y(v[i]));
  cairo_stroke(cr);
}

// Events as lines across the panel, drawn under the curves.
void events(cairo_t* cr, const PlotPanel& p, const std::vector<double>& times_s, const Rgb& c) {
  set_color(cr, c, 0.55);
  cairo_set_line_width(cr, 1.5);
  for (double t : times_s) line(cr, p.x(t), p.y0, p.x(t), p.y0 + p.h);
  cairo_stroke(cr);
}

struct LegendEntry {
  std::string name;
  Rgb color;
  bool event;  // drawn as a short vertical line (an event), else as a horizontal one (a curve)
};

// The legend above the panel's top-right corner, on one line with the panel's label, so it
// covers no data.
void legend(cairo_t* cr, const PlotPanel& p, const std::vector<LegendEntry>& entries) {
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 14);
  constexpr double kSample = 28, kPad = 6, kSpace = 22;  // line sample, sample to name, between entries
  std::vector<double> widths;
  double total = 0;
  for (const LegendEntry& e : entries) {
    cairo_text_extents_t ext;
    cairo_text_extents(cr, e.name.c_str(), &ext);
    widths.push_back(ext.x_advance);
    total += kSample + kPad + ext.x_advance + (total > 0 ? kSpace : 0);
  }
  double x = p.x0 + p.w - total;
  const double mid = p.y0 - 17;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    set_color(cr, entries[i].color);
    cairo_set_line_width(cr, entries[i].event ? 2.0 : 2.5);
    if (entries[i].event)
      line(cr, x + 0.5 * kSample, mid - 7, x + 0.5 * kSample, mid + 7);
    else
      line(cr, x, mid, x + kSample, mid);
    cairo_stroke(cr);
    set_color(cr, kInk);
    text(cr, x + kSample + kPad, mid + 5, entries[i].name, 14);
    x += kSample + kPad + widths[i] + kSpace;
  }
}

void draw(cairo_t* cr, const EvaluationPlot& plot, const PlotLayout& L) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  set_color(cr, kInk);
  text(cr, L.speed.x0, 30, plot.title, 16);

  // Joint speed, with the junctions under the curves.
  axes(cr, L.speed, L.speed_axis, L.time, "Mean joint speed (cm/s)", false);
  clip_to(cr, L.speed);
  events(cr, L.speed, plot.junctions_s, kJunction);
  curve(cr, L.speed, plot.truth_speed, 1.0 / plot.fps, kTruth);
  curve(cr, L.speed, plot.generated_speed, 1.0 / plot.fps, kGenerated);
  cairo_restore(cr);
  std::vector<LegendEntry> entries = {{"generated", kGenerated, false}};
  if (!plot.truth_speed.empty()) entries.push_back({"truth", kTruth, false});
  if (!plot.junctions_s.empty()) entries.push_back({"junction", kJunction, true});
  legend(cr, L.speed, entries);

  // Onset strength, with the onsets under the curve.
  axes(cr, L.audio, plot.envelope.empty() ? PlotAxis{} : L.audio_axis, L.time, "Onset strength (dB)", true);
  if (plot.envelope.empty()) {
    set_color(cr, kInk);
    text(cr, L.audio.x0 + 0.5 * L.audio.w, L.audio.y0 + 0.5 * L.audio.h, "no audio", 16, 0.5);
  } else {
    clip_to(cr, L.audio);
    events(cr, L.audio, plot.onsets_s, kOnset);
    curve(cr, L.audio, std::vector<double>(plot.envelope.begin(), plot.envelope.end()), 512.0 / 22050.0, kEnvelope);
    cairo_restore(cr);
    entries = {{"onset strength", kEnvelope, false}};
    if (!plot.onsets_s.empty()) entries.push_back({"onset", kOnset, true});
    legend(cr, L.audio, entries);
  }
  set_color(cr, kInk);
  text(cr, L.audio.x0 + 0.5 * L.audio.w, L.audio.y0 + L.audio.h + 52, "Time (s)", 16, 0.5, CAIRO_FONT_WEIGHT_BOLD);
}

}  // namespace

PlotLayout plot_layout(const EvaluationPlot& plot) {
  PlotLayout L;
  L.width = kWidth;
  L.height = kHeight;
  const double duration = std::max(1e-6, static_cast<double>(plot.generated_speed.size()) / plot.fps);
  L.time = plot_axis(duration, 12, false);
  L.speed_axis = value_axis(largest(plot.generated_speed, plot.truth_speed));
  L.audio_axis = value_axis(largest(std::vector<double>(plot.envelope.begin(), plot.envelope.end()), {}));
  const double w = kWidth - kLeft - kRight;
  L.speed = PlotPanel{kLeft, kTop, w, kPanelH, duration, L.speed_axis.ticks.back()};
  L.audio = PlotPanel{kLeft, kTop + kPanelH + kGap, w, kPanelH, duration, L.audio_axis.ticks.back()};
  return L;
}

const std::vector<std::string> kPlotExtensions = {".png", ".svg"};

void plot_write(const std::string& path, const EvaluationPlot& plot) {
  const bool svg = ends_with_ci(path, ".svg");
  if (!svg && !ends_with_ci(path, ".png")) throw Error(path + ": the plot must be a .png or .svg file");
  if (plot.generated_speed.empty() || !(plot.fps > 0)) throw Error(path + ": nothing to plot");
  for (const std::vector<double>* v : {&plot.generated_speed, &plot.truth_speed})
    for (double x : *v)
      if (!std::isfinite(x)) throw Error(path + ": cannot plot a joint speed that is not a number");
  for (float x : plot.envelope)
    if (!std::isfinite(x)) throw Error(path + ": cannot plot an onset strength that is not a number");
  const PlotLayout layout = plot_layout(plot);
  std::string bytes;
  cairo_surface_t* surface =
      svg ? cairo_svg_surface_create_for_stream(append_to_string, &bytes, kWidth, kHeight)
          : cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(kWidth), static_cast<int>(kHeight));
  cairo_t* cr = cairo_create(surface);
  draw(cr, plot, layout);
  cairo_destroy(cr);
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  if (svg) {
    cairo_surface_finish(surface);
    status = cairo_surface_status(surface);
  } else {
    status = cairo_surface_write_to_png_stream(surface, append_to_string, &bytes);
  }
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS)
    throw Error(path + ": cannot draw the plot (" + cairo_status_to_string(status) + ")");
  write_file_atomically(
      path, [&](std::ostream& os) { os.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); }, true);
}

}  // namespace gmg
