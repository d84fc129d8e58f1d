// The event strip of `gmg render --report` marks the stretches a reenactment kept from an earlier
// output, planned afresh and pinned (engine/render/overlay.h), each in its own colour.
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include <cairo.h>
#include <gtest/gtest.h>

#include "engine/render/overlay.h"

namespace gmg::render {
namespace {

// The pixel at (x, y) of a 32-bit image surface as 0xRRGGBB.
std::uint32_t rgb_at(cairo_surface_t* s, int x, int y) {
  cairo_surface_flush(s);
  const unsigned char* row = cairo_image_surface_get_data(s) + y * cairo_image_surface_get_stride(s);
  std::uint32_t v = 0;
  std::memcpy(&v, row + 4 * x, 4);
  return v & 0xFFFFFFu;
}

TEST(OverlayControl, TheStripsBottomBandShowsKeptPlannedAndPinned) {
  // 6 s across 600 px: 100 px a second, t = 10 s at x = 300.
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 600, 40);
  cairo_t* cr = cairo_create(s);
  Markers m;
  m.kept_s = {{0.0, 9.0}};
  m.planned_s = {{9.0, 11.0}};
  m.pinned_s = {{11.0, 12.0}};
  draw_marker_strip(cr, m, 10.0, Rect{0, 0, 600, 40});
  struct Rgb {
    int r, g, b;
  };
  auto at = [&](int x, int y) {
    const std::uint32_t v = rgb_at(s, x, y);
    return Rgb{static_cast<int>(v >> 16), static_cast<int>((v >> 8) & 0xFF), static_cast<int>(v & 0xFF)};
  };
  const Rgb kept = at(150, 38), planned = at(250, 38), pinned = at(450, 38), none = at(550, 38), above = at(150, 20);
  // 8.5 s kept: a light grey; 9.5 s planned: amber; 11.5 s pinned: violet; 12.5 s: the strip's dark
  // background, as above the band.
  EXPECT_TRUE(kept.r > 120 && std::abs(kept.r - kept.g) < 20 && std::abs(kept.g - kept.b) < 30);
  EXPECT_TRUE(planned.r > 200 && planned.g > 150 && planned.b < 80);
  EXPECT_TRUE(pinned.b > 200 && pinned.r > pinned.g + 40);
  EXPECT_TRUE(none.r < 60 && none.g < 60 && none.b < 60);
  EXPECT_TRUE(above.r < 60 && above.g < 60 && above.b < 60);
  cairo_destroy(cr);
  cairo_surface_destroy(s);
}

}  // namespace
}  // namespace gmg::render
