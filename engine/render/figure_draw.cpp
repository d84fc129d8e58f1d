// Drawing a Figure (figure.h) with Cairo: painter's order, cylinder shading, depth fog, shadow.
#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/core/math.h"
#include "engine/render/figure.h"

namespace gmg::render {
namespace {

// The light comes from the upper left of the picture and somewhat from the viewer: brightness
// across a cylinder at s in [-1, 1] (-1 the side away from the light) is ambient plus Lambert.
constexpr double kLightX = -0.55, kLightY = -0.83;
constexpr double kShade[][2] = {{0.0, 0.42}, {0.25, 0.52}, {0.5, 0.78}, {0.72, 0.97}, {0.86, 1.06}, {1.0, 0.86}};
constexpr double kFogMax = 0.5;        // how far the farthest part fades towards the background
constexpr double kShadowAlpha = 0.22;  // darkness of the floor shadow

struct Capsule {
  ScreenPoint a, b;
  double ra = 0, rb = 0;  // pixels
  glm::dvec3 color{0.0};
  bool sphere = false;  // the head: a ball at a with radius ra
  double depth = 0;
};

glm::dvec3 side_color(const glm::dvec3& c, int side) {
  if (side > 0) return glm::min(c * 1.18 + glm::dvec3(0.04), glm::dvec3(1.0));
  if (side < 0) return c * 0.82;
  return c;
}

glm::dvec3 shaded(const glm::dvec3& c, double light, double fog, const glm::dvec3& fog_color) {
  const glm::dvec3 lit = glm::min(c * light + glm::dvec3(std::max(0.0, light - 1.0) * 0.6), glm::dvec3(1.0));
  return lit * (1.0 - fog) + fog_color * fog;
}

// A tapered capsule: the hull of two circles.
void capsule_path(cairo_t* cr, double ax, double ay, double ra, double bx, double by, double rb) {
  const double dx = bx - ax, dy = by - ay, d = std::hypot(dx, dy);
  cairo_new_path(cr);
  if (d <= std::abs(ra - rb) + 1e-6) {
    const bool a_larger = ra >= rb;
    cairo_arc(cr, a_larger ? ax : bx, a_larger ? ay : by, std::max(ra, rb), 0, kTwoPi);
    cairo_close_path(cr);
    return;
  }
  const double beta = std::atan2(dy, dx), alpha = std::acos((ra - rb) / d);
  cairo_arc(cr, ax, ay, ra, beta + alpha, beta + kTwoPi - alpha);
  cairo_arc(cr, bx, by, rb, beta - alpha, beta + alpha);
  cairo_close_path(cr);
}

double fog_at(const Camera& camera, double depth) {
  const double span = std::max(camera.far_depth - camera.near_depth, 1e-6);
  return std::clamp((depth - camera.near_depth) / span, 0.0, 1.0) * kFogMax;
}

void draw_capsule(cairo_t* cr, const Camera& camera, const Capsule& c, const glm::dvec3& fog_color) {
  const double fog = fog_at(camera, c.depth);
  const glm::dvec3 edge = shaded(c.color, 0.3, fog, fog_color);
  cairo_pattern_t* pattern = nullptr;
  if (c.sphere) {
    const double r = c.ra;
    pattern =
        cairo_pattern_create_radial(c.a.x + kLightX * r * 0.4, c.a.y + kLightY * r * 0.4, r * 0.05, c.a.x, c.a.y, r);
    for (const double* s : {kShade[4], kShade[3], kShade[2], kShade[0]}) {
      const glm::dvec3 col = shaded(c.color, s[1], fog, fog_color);
      cairo_pattern_add_color_stop_rgb(pattern, 1.0 - s[0], col.r, col.g, col.b);
    }
    cairo_new_path(cr);
    cairo_arc(cr, c.a.x, c.a.y, r, 0, kTwoPi);
  } else {
    // Across the capsule, from the side away from the light to the side facing it.
    double nx = -(c.b.y - c.a.y), ny = c.b.x - c.a.x;
    const double len = std::hypot(nx, ny);
    if (len > 1e-9)
      nx /= len, ny /= len;
    else
      nx = -kLightX, ny = -kLightY;  // seen end-on: a ball, lit like one
    if (nx * kLightX + ny * kLightY < 0) nx = -nx, ny = -ny;
    const double r = std::max(c.ra, c.rb);
    const double mx = (c.a.x + c.b.x) / 2, my = (c.a.y + c.b.y) / 2;
    pattern = cairo_pattern_create_linear(mx - nx * r, my - ny * r, mx + nx * r, my + ny * r);
    for (const auto& s : kShade) {
      const glm::dvec3 col = shaded(c.color, s[1], fog, fog_color);
      cairo_pattern_add_color_stop_rgb(pattern, s[0], col.r, col.g, col.b);
    }
    capsule_path(cr, c.a.x, c.a.y, c.ra, c.b.x, c.b.y, c.rb);
  }
  cairo_set_source(cr, pattern);
  cairo_fill_preserve(cr);
  cairo_pattern_destroy(pattern);
  cairo_set_source_rgb(cr, edge.r, edge.g, edge.b);
  cairo_set_line_width(cr, 1.0);
  cairo_stroke(cr);
}

// The outline of a tapered capsule lying on the floor, as a polygon in world space, projected:
// exact perspective for the shadow, however flat the camera looks at the floor.
void floor_capsule_path(cairo_t* cr, const Camera& camera, glm::dvec3 a, double ra, glm::dvec3 b, double rb,
                        double floor_y) {
  a.y = b.y = floor_y;
  const glm::dvec3 d = b - a;
  const double len = glm::length(d);
  cairo_new_path(cr);
  constexpr int kSteps = 8;
  auto point = [&](const glm::dvec3& c, double r, double angle, const glm::dvec3& u, const glm::dvec3& v) {
    const ScreenPoint s = camera_project(camera, c + (u * std::cos(angle) + v * std::sin(angle)) * r);
    cairo_line_to(cr, s.x, s.y);
  };
  if (len <= std::abs(ra - rb) + 1e-6) {
    const glm::dvec3 u(1, 0, 0), v(0, 0, 1);
    for (int k = 0; k < 2 * kSteps; ++k) point(ra >= rb ? a : b, std::max(ra, rb), k * kPi / kSteps, u, v);
    cairo_close_path(cr);
    return;
  }
  const glm::dvec3 u = d / len, v(-u.z, 0, u.x);
  const double alpha = std::acos((ra - rb) / len);
  for (int k = 0; k <= kSteps; ++k) point(a, ra, alpha + (kTwoPi - 2 * alpha) * k / kSteps, u, v);
  for (int k = 0; k <= kSteps; ++k) point(b, rb, -alpha + 2 * alpha * k / kSteps, u, v);
  cairo_close_path(cr);
}

void draw_shadow(cairo_t* cr, const Camera& camera, const Figure& f, int frame, double floor_y) {
  cairo_push_group(cr);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.12);
  for (const Bone& b : f.bones) {
    floor_capsule_path(cr, camera, figure_point(f, frame, b.a), f.radius_cm[static_cast<std::size_t>(b.a)],
                       figure_point(f, frame, b.b), f.radius_cm[static_cast<std::size_t>(b.b)], floor_y);
    cairo_fill(cr);
  }
  if (f.head >= 0) {
    const glm::dvec3 c = figure_head_center(f, frame);
    floor_capsule_path(cr, camera, c, f.head_radius_cm, c, f.head_radius_cm, floor_y);
    cairo_fill(cr);
  }
  cairo_pop_group_to_source(cr);
  cairo_paint_with_alpha(cr, kShadowAlpha);
}

}  // namespace

void draw_figure(cairo_t* cr, const Camera& camera, const Figure& f, int frame, const FigureStyle& style) {
  draw_shadow(cr, camera, f, frame, style.floor_y);
  std::vector<Capsule> parts;
  parts.reserve(f.bones.size() + 1);
  for (const Bone& b : f.bones) {
    Capsule c;
    c.a = camera_project(camera, figure_point(f, frame, b.a));
    c.b = camera_project(camera, figure_point(f, frame, b.b));
    c.ra = camera_pixels(camera, f.radius_cm[static_cast<std::size_t>(b.a)], c.a.depth);
    c.rb = camera_pixels(camera, f.radius_cm[static_cast<std::size_t>(b.b)], c.b.depth);
    const int side = f.side[static_cast<std::size_t>(b.b)] != 0 ? f.side[static_cast<std::size_t>(b.b)]
                                                                : f.side[static_cast<std::size_t>(b.a)];
    c.color = side_color(style.color, side);
    c.depth = (c.a.depth + c.b.depth) / 2;
    parts.push_back(c);
  }
  if (f.head >= 0) {
    Capsule h;
    h.sphere = true;
    h.a = camera_project(camera, figure_head_center(f, frame));
    h.ra = camera_pixels(camera, f.head_radius_cm, h.a.depth);
    h.color = style.color;
    h.depth = h.a.depth;
    parts.push_back(h);
    Capsule nose = h;
    nose.a = camera_project(camera, figure_point(f, frame, f.nose));
    nose.ra = camera_pixels(camera, f.radius_cm[static_cast<std::size_t>(f.nose)], nose.a.depth);
    nose.color = style.color * 0.8;
    nose.depth = nose.a.depth;
    parts.push_back(nose);
  }
  // Painter's order, far to near; stable so equal depths keep the skeleton's order.
  std::stable_sort(parts.begin(), parts.end(), [](const Capsule& x, const Capsule& y) { return x.depth > y.depth; });
  for (const Capsule& c : parts) draw_capsule(cr, camera, c, style.fog);
}

void draw_floor(cairo_t* cr, const Camera& camera, const Box& box, double floor_y) {
  constexpr double kTile = 50.0;  // cm
  const double diagonal = std::max(glm::length(box.hi - box.lo), 1.0);
  const double extent = std::max(box.hi.x - box.lo.x, box.hi.z - box.lo.z);
  // Whole tiles, and never so large that the floor's near edge reaches behind the eye.
  const int tiles = std::max(2, static_cast<int>(std::min(0.8 * extent + 80.0, 1.4 * diagonal) / kTile));
  const double cx = std::round((box.lo.x + box.hi.x) / 2 / kTile) * kTile;
  const double cz = std::round((box.lo.z + box.hi.z) / 2 / kTile) * kTile;
  auto to = [&](double x, double z, bool move) {
    const ScreenPoint s = camera_project(camera, glm::dvec3(x, floor_y, z));
    if (move)
      cairo_move_to(cr, s.x, s.y);
    else
      cairo_line_to(cr, s.x, s.y);
  };
  for (int i = -tiles; i < tiles; ++i) {
    for (int k = -tiles; k < tiles; ++k) {
      const double x0 = cx + i * kTile, z0 = cz + k * kTile;
      // Tiles fade out towards the edge so the floor has no hard border.
      const double r = std::max(std::abs(i + 0.5), std::abs(k + 0.5)) / tiles;
      const double tone = ((i + k) & 1) ? 0.80 : 0.74;
      const double v = tone + (0.86 - tone) * r * r;
      cairo_set_source_rgb(cr, v, v, v * 0.98);
      to(x0, z0, true), to(x0 + kTile, z0, false), to(x0 + kTile, z0 + kTile, false), to(x0, z0 + kTile, false);
      cairo_close_path(cr);
      cairo_fill_preserve(cr);
      cairo_set_line_width(cr, 0.6);
      cairo_stroke(cr);  // same colour: closes the hairline seams antialiasing leaves between tiles
    }
  }
}

}  // namespace gmg::render
