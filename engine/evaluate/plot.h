// The picture of `gmg evaluate --plot`: over time, the mean joint speed of the generated motion and
// of the truth with the path junctions, and below it the speech's onset strength with its onsets.
// Drawn with Cairo; PNG or SVG by the file's extension.
//
// Made to go into a paper as it is: both panels share a time axis in seconds; each value axis
// starts at 0, is labelled with its unit and has ticks at 1, 2 or 5 times a power of ten, its top
// tick above the largest value (no curve is cut off); a legend names every line; onsets and
// junctions are lines across their panel, under the curves.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace gmg {

struct EvaluationPlot {
  double fps = 30.0;
  std::string title;
  std::vector<double> generated_speed;  // cm/s per frame (required)
  std::vector<double> truth_speed;      // cm/s per frame; empty = none
  std::vector<float> envelope;          // onset strength per envelope frame (512 samples at 22050 Hz); empty = none
  std::vector<double> onsets_s;         // audio onsets (s)
  std::vector<double> junctions_s;      // where the output's source jumps (s)
};

// Mean over joints of the root-relative joint speed (cm/s) at each frame (frame 0 takes frame 1's).
std::vector<double> mean_joint_speed(const Eigen::MatrixXd& pos, double fps);

// The ticks of an axis from 0: a step of 1, 2 or 5 times a power of ten, the smallest that reaches
// `top` (> 0, finite) in at most max_intervals (>= 1) intervals. cover: the last tick is the
// first at or above top (a value axis, which must hold every value); else the last at or below
// it (a time axis, which ends with the data).
struct PlotAxis {
  double step = 1;
  std::vector<double> ticks;  // 0, step, 2 step, ...
};
PlotAxis plot_axis(double top, int max_intervals, bool cover);

// A tick's label: as many decimals as the step needs ("0", "2.5", "0.05").
std::string plot_tick_label(double value, double step);

// Where a panel is drawn (pixels, y down) and the values it shows.
struct PlotPanel {
  double x0 = 0, y0 = 0, w = 0, h = 0;
  double t_max = 1;  // seconds at the right edge
  double v_max = 1;  // value at the top edge: the value axis' last tick
  double x(double t) const { return x0 + w * t / t_max; }
  double y(double v) const { return y0 + h - h * v / v_max; }
};

struct PlotLayout {
  double width = 0, height = 0;  // the picture, pixels
  PlotPanel speed, audio;        // joint speed above, onset strength below
  PlotAxis time, speed_axis, audio_axis;
};

// The layout of a plot's picture. The value axes cover 1.04 times the largest value (the
// speeds of both curves; the onset strength), so the highest peak stays below the frame.
PlotLayout plot_layout(const EvaluationPlot& plot);

// The picture formats plot_write writes: {".png", ".svg"}.
extern const std::vector<std::string> kPlotExtensions;

// Writes the picture atomically. gmg::Error naming the file for an extension other than .png or
// .svg, an empty speed curve, a non-finite speed, or a failed write.
void plot_write(const std::string& path, const EvaluationPlot& plot);

}  // namespace gmg
