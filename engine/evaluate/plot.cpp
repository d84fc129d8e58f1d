#include "engine/evaluate/plot.h"

#include <algorithm>
#include <cmath>
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

namespace {

constexpr double kWidth = 1600, kHeight = 640, kLeft = 70, kRight = 20, kTop = 40, kBottom = 40, kGap = 30;

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// A panel: a box on the canvas mapping (seconds, value) to pixels.
struct Panel {
  double x0, y0, w, h, t_max, v_max;
  double x(double t) const { return x0 + w * t / t_max; }
  double y(double v) const { return y0 + h - h * std::min(v, v_max) / v_max; }
};

void text(cairo_t* cr, double x, double y, const std::string& s, double size = 13) {
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

void frame(cairo_t* cr, const Panel& p, const std::string& label) {
  cairo_set_source_rgb(cr, 0.75, 0.75, 0.75);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, p.x0, p.y0, p.w, p.h);
  cairo_stroke(cr);
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  text(cr, p.x0 + 6, p.y0 + 16, label);
  text(cr, 8, p.y0 + 12, format_number(std::round(p.v_max * 10) / 10));
  text(cr, 8, p.y0 + p.h, "0");
}

void curve(cairo_t* cr, const Panel& p, const std::vector<double>& v, double dt, double r, double g, double b) {
  if (v.empty()) return;
  cairo_set_source_rgb(cr, r, g, b);
  cairo_set_line_width(cr, 1.3);
  cairo_move_to(cr, p.x(0), p.y(v[0]));
  for (std::size_t i = 1; i < v.size(); ++i) cairo_line_to(cr, p.x(static_cast<double>(i) * dt), p.y(v[i]));
  cairo_stroke(cr);
}

void vertical(cairo_t* cr, const Panel& p, double t, double top, double bottom) {
  cairo_move_to(cr, p.x(t), top);
  cairo_line_to(cr, p.x(t), bottom);
}

double top_of(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 1e-9;
  // The 99.5th percentile rather than the maximum, so one spike does not flatten the curves.
  std::vector<double> all = a;
  all.insert(all.end(), b.begin(), b.end());
  if (!all.empty()) m = std::max(m, percentile(all, 99.5) * 1.1);
  return m;
}

void draw(cairo_t* cr, const EvaluationPlot& plot) {
  const double duration = std::max(1e-6, static_cast<double>(plot.generated_speed.size()) / plot.fps);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  text(cr, kLeft, 24, plot.title, 15);
  const double inner_w = kWidth - kLeft - kRight;
  const double panel_h = (kHeight - kTop - kBottom - kGap) / 2;
  const Panel speed{kLeft, kTop, inner_w, panel_h, duration, top_of(plot.generated_speed, plot.truth_speed)};
  std::vector<double> env(plot.envelope.begin(), plot.envelope.end());
  const Panel audio{kLeft, kTop + panel_h + kGap, inner_w, panel_h, duration, top_of(env, {})};

  // Junctions across both panels, under the curves.
  cairo_set_source_rgba(cr, 0.85, 0.1, 0.1, 0.45);
  cairo_set_line_width(cr, 1.0);
  for (double t : plot.junctions_s) vertical(cr, speed, t, speed.y0, audio.y0 + audio.h);
  cairo_stroke(cr);

  frame(cr, speed,
        "mean joint speed, cm/s: generated (blue)" + std::string(plot.truth_speed.empty() ? "" : ", truth (grey)") +
            (plot.junctions_s.empty() ? "" : "; junctions (red)"));
  curve(cr, speed, plot.truth_speed, 1.0 / plot.fps, 0.55, 0.55, 0.55);
  curve(cr, speed, plot.generated_speed, 1.0 / plot.fps, 0.1, 0.3, 0.85);

  frame(cr, audio, plot.envelope.empty() ? "no audio" : "onset strength (orange), onsets (green)");
  curve(cr, audio, env, 512.0 / 22050.0, 0.95, 0.55, 0.1);
  cairo_set_source_rgb(cr, 0.1, 0.6, 0.2);
  cairo_set_line_width(cr, 1.5);
  for (double t : plot.onsets_s) vertical(cr, audio, t, audio.y0 + audio.h - 12, audio.y0 + audio.h);
  cairo_stroke(cr);

  // Time axis: a tick every second, a label every 5.
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  cairo_set_line_width(cr, 1.0);
  const double axis_y = audio.y0 + audio.h;
  for (int s = 0; s <= static_cast<int>(duration); ++s) {
    vertical(cr, audio, s, axis_y, axis_y + (s % 5 == 0 ? 8 : 4));
    if (s % 5 == 0) text(cr, audio.x(s) - 6, axis_y + 22, std::to_string(s) + " s", 12);
  }
  cairo_stroke(cr);
}

}  // namespace

const std::vector<std::string> kPlotExtensions = {".png", ".svg"};

void plot_write(const std::string& path, const EvaluationPlot& plot) {
  const bool svg = ends_with_ci(path, ".svg");
  if (!svg && !ends_with_ci(path, ".png")) throw Error(path + ": the plot must be a .png or .svg file");
  if (plot.generated_speed.empty() || !(plot.fps > 0)) throw Error(path + ": nothing to plot");
  std::string bytes;
  cairo_surface_t* surface =
      svg ? cairo_svg_surface_create_for_stream(append_to_string, &bytes, kWidth, kHeight)
          : cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(kWidth), static_cast<int>(kHeight));
  cairo_t* cr = cairo_create(surface);
  draw(cr, plot);
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
