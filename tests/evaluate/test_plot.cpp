// The picture of gmg evaluate --plot: its axes (ticks at 1, 2, 5 times a power of ten, value axes
// that hold every value), and what its PNG shows, read back pixel by pixel: peaks below the top of
// their panel, onsets and junctions as lines across their panels.
#include <gtest/gtest.h>

#include <cairo.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/evaluate/plot.h"
#include "tests/test_support.h"

namespace {

using gmg::EvaluationPlot;
using gmg::PlotAxis;

std::vector<double> ticks(const PlotAxis& a) { return a.ticks; }

TEST(PlotAxis, StepsOfOneTwoOrFiveTimesAPowerOfTen) {
  // A value axis covers its top: 11.6 in at most 5 intervals takes steps of 5 (2 would need 6).
  PlotAxis a = gmg::plot_axis(11.6, 5, true);
  EXPECT_EQ(a.step, 5.0);
  EXPECT_EQ(ticks(a), (std::vector<double>{0, 5, 10, 15}));
  // A top on a tick is that tick.
  a = gmg::plot_axis(10.0, 5, true);
  EXPECT_EQ(a.step, 2.0);
  EXPECT_EQ(ticks(a), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  // 28.6: 5 would need 6 intervals, so 10.
  EXPECT_EQ(ticks(gmg::plot_axis(28.6, 5, true)), (std::vector<double>{0, 10, 20, 30}));
  // Below 1: 0.3 in steps of 0.1.
  a = gmg::plot_axis(0.3, 5, true);
  EXPECT_DOUBLE_EQ(a.step, 0.1);
  ASSERT_EQ(a.ticks.size(), 4u);
  EXPECT_NEAR(a.ticks.back(), 0.3, 1e-12);
  // A time axis ends at or before its top: 20 s in at most 12 intervals, every 2 s; 61 s every 5 s.
  a = gmg::plot_axis(20.0, 12, false);
  EXPECT_EQ(a.step, 2.0);
  EXPECT_EQ(a.ticks.size(), 11u);
  EXPECT_EQ(a.ticks.back(), 20.0);
  a = gmg::plot_axis(61.0, 12, false);
  EXPECT_EQ(a.step, 5.0);
  EXPECT_EQ(a.ticks.back(), 60.0);
  EXPECT_THROW(gmg::plot_axis(0.0, 5, true), gmg::Error);
  EXPECT_THROW(gmg::plot_axis(std::nan(""), 5, true), gmg::Error);
  EXPECT_THROW(gmg::plot_axis(1.0, 0, true), gmg::Error);
}

TEST(PlotAxis, LabelsHaveTheDecimalsOfTheStep) {
  EXPECT_EQ(gmg::plot_tick_label(10.0, 5.0), "10");
  EXPECT_EQ(gmg::plot_tick_label(2.5, 0.5), "2.5");
  EXPECT_EQ(gmg::plot_tick_label(0.0, 0.2), "0.0");
  EXPECT_EQ(gmg::plot_tick_label(0.15, 0.05), "0.15");
  EXPECT_EQ(gmg::plot_tick_label(300.0, 100.0), "300");
}

// 20 s at 30 fps: a slow speed curve with one spike to 11.6 cm/s at 5 s, onset strength peaks at
// the onsets, a junction.
EvaluationPlot sample_plot() {
  EvaluationPlot p;
  p.title = "sample";
  for (int f = 0; f < 600; ++f) p.generated_speed.push_back(f == 150 ? 11.6 : 2.0 + std::sin(f * 0.05));
  p.onsets_s = {2.0, 7.5, 13.0};
  const double hop = 512.0 / 22050.0;
  for (int k = 0; k * hop < 20.0; ++k) {
    double v = 0.5;
    for (double o : p.onsets_s)
      if (std::abs(k * hop - o) < 0.03) v = 27.5;
    p.envelope.push_back(static_cast<float>(v));
  }
  p.junctions_s = {10.0};
  return p;
}

TEST(Plot, ValueAxesHoldTheHighestPeak) {
  const EvaluationPlot p = sample_plot();
  const gmg::PlotLayout L = gmg::plot_layout(p);
  EXPECT_EQ(L.speed.v_max, 15.0);  // 1.04 x 11.6 = 12.1, in steps of 5
  EXPECT_EQ(L.audio.v_max, 30.0);  // 1.04 x 27.5 = 28.6, in steps of 10
  EXPECT_EQ(L.time.step, 2.0);
  EXPECT_EQ(L.speed.t_max, 20.0);
  // The panels are one above the other, inside the picture, sharing the time axis.
  EXPECT_EQ(L.speed.x0, L.audio.x0);
  EXPECT_EQ(L.speed.w, L.audio.w);
  EXPECT_LT(L.speed.y0 + L.speed.h, L.audio.y0);
  EXPECT_LT(L.audio.y0 + L.audio.h, L.height);
}

// The PNG's pixels: 0x00RRGGBB.
struct Picture {
  std::vector<std::uint32_t> px;
  int w = 0, h = 0;
  explicit Picture(const std::string& path) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
    w = cairo_image_surface_get_width(s);
    h = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) px.push_back(reinterpret_cast<const std::uint32_t*>(data + y * stride)[x]);
    cairo_surface_destroy(s);
  }
  int r(int x, int y) const { return static_cast<int>(px[static_cast<std::size_t>(y * w + x)] >> 16 & 255); }
  int g(int x, int y) const { return static_cast<int>(px[static_cast<std::size_t>(y * w + x)] >> 8 & 255); }
  int b(int x, int y) const { return static_cast<int>(px[static_cast<std::size_t>(y * w + x)] & 255); }
  bool blue(int x, int y) const { return b(x, y) > r(x, y) + 60 && b(x, y) > g(x, y) + 30; }
  bool green(int x, int y) const { return g(x, y) > r(x, y) + 40 && g(x, y) > b(x, y) + 30; }
  bool red(int x, int y) const { return r(x, y) > g(x, y) + 50 && r(x, y) > b(x, y) + 50; }
};

TEST(Plot, PeaksStayInsideAndEventsCrossTheirPanels) {
  gmg::testing::TempDir dir;
  const EvaluationPlot p = sample_plot();
  gmg::plot_write(dir.file("p.png"), p);
  const Picture pic(dir.file("p.png"));
  const gmg::PlotLayout L = gmg::plot_layout(p);
  ASSERT_EQ(pic.w, static_cast<int>(L.width));
  ASSERT_EQ(pic.h, static_cast<int>(L.height));
  // The spike: its highest blue pixel where 11.6 cm/s is on the axis (15 at the top), well below
  // the panel's top edge, not cut flat along it.
  const int spike_x = static_cast<int>(std::lround(L.speed.x(5.0)));
  int top = -1;
  for (int y = static_cast<int>(L.speed.y0); y < static_cast<int>(L.speed.y0 + L.speed.h) && top < 0; ++y)
    for (int x = spike_x - 2; x <= spike_x + 2; ++x)
      if (pic.blue(x, y)) top = y;
  ASSERT_GE(top, 0);
  EXPECT_NEAR(top, L.speed.y(11.6), 3.0);
  EXPECT_GT(top, L.speed.y0 + 0.2 * L.speed.h);
  // Each onset: a green line over at least 90 % of the onset panel's height.
  for (double t : p.onsets_s) {
    const int x = static_cast<int>(std::lround(L.audio.x(t)));
    int rows = 0;
    for (int y = static_cast<int>(L.audio.y0); y < static_cast<int>(L.audio.y0 + L.audio.h); ++y)
      if (pic.green(x, y) || pic.green(x - 1, y) || pic.green(x + 1, y)) ++rows;
    EXPECT_GT(rows, 0.9 * L.audio.h) << "onset at " << t << " s";
  }
  // Away from any onset no green line.
  int stray = 0;
  const int quiet_x = static_cast<int>(std::lround(L.audio.x(5.0)));
  for (int y = static_cast<int>(L.audio.y0); y < static_cast<int>(L.audio.y0 + L.audio.h); ++y)
    stray += pic.green(quiet_x, y) ? 1 : 0;
  EXPECT_EQ(stray, 0);
  // The junction: a red line across the speed panel.
  const int jx = static_cast<int>(std::lround(L.speed.x(10.0)));
  int red = 0;
  for (int y = static_cast<int>(L.speed.y0); y < static_cast<int>(L.speed.y0 + L.speed.h); ++y)
    if (pic.red(jx, y) || pic.red(jx - 1, y) || pic.red(jx + 1, y)) ++red;
  EXPECT_GT(red, 0.9 * L.speed.h);
}

TEST(Plot, RefusesWhatItCannotDraw) {
  gmg::testing::TempDir dir;
  EvaluationPlot p = sample_plot();
  p.generated_speed[3] = std::nan("");
  EXPECT_THROW(gmg::plot_write(dir.file("p.png"), p), gmg::Error);
  p.generated_speed.clear();
  EXPECT_THROW(gmg::plot_write(dir.file("p.png"), p), gmg::Error);
  EXPECT_FALSE(std::filesystem::exists(dir.file("p.png")));
}

}  // namespace
