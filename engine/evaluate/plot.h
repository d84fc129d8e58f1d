// The picture of `gmg evaluate --plot`: over time, the mean joint speed of the generated motion and
// of the truth, the speech's onset strength with its onsets, and the path junctions. Drawn with
// Cairo; PNG or SVG by the file's extension.
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

// The picture formats plot_write writes: {".png", ".svg"}.
extern const std::vector<std::string> kPlotExtensions;

// Writes the picture atomically. gmg::Error naming the file for an extension other than .png or
// .svg, an empty speed curve, or a failed write.
void plot_write(const std::string& path, const EvaluationPlot& plot);

}  // namespace gmg
