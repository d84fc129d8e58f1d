#include "engine/render/camera.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/math.h"
#include "engine/core/strings.h"

namespace gmg::render {
namespace {

constexpr glm::dvec3 kUp{0, 1, 0};
// Looking slightly down shows the floor as a plane, the strongest cue that the figure is 3D.
constexpr double kElevationDeg = 12.0;

glm::dvec3 floor_direction(const glm::dvec3& facing) {
  const glm::dvec3 f = facing - kUp * glm::dot(facing, kUp);
  return glm::length(f) > 1e-9 ? glm::normalize(f) : glm::dvec3(0, 0, 1);
}

}  // namespace

View parse_view(const std::string& name) {
  const std::string n = ascii_lower(name);
  if (n == "front") return View::Front;
  if (n == "side") return View::Side;
  if (n == "top") return View::Top;
  throw Error("--view: '" + name + "' is not a view (choose front, side or top)");
}

Camera camera_fit(const Box& box, const glm::dvec3& facing, View view, const Rect& area, double margin) {
  const glm::dvec3 forward = floor_direction(facing);
  const glm::dvec3 left = glm::cross(kUp, forward);
  const double e = kElevationDeg * kDegToRad;
  Camera c;
  glm::dvec3 screen_up_hint = kUp;
  if (view == View::Front) {
    c.back = glm::normalize(forward * std::cos(e) + kUp * std::sin(e));
  } else if (view == View::Side) {
    c.back = glm::normalize(left * std::cos(e) + kUp * std::sin(e));
  } else {
    c.back = kUp;
    screen_up_hint = -forward;
  }
  c.right = glm::normalize(glm::cross(screen_up_hint, c.back));
  c.up = glm::cross(c.back, c.right);
  const glm::dvec3 center = (box.lo + box.hi) * 0.5;
  const double diagonal = std::max(glm::length(box.hi - box.lo), 1.0);
  // Two diagonals away: mild perspective. From above, the body's height is all depth, so the eye
  // keeps further back or the head would dwarf the feet.
  c.eye = center + c.back * ((view == View::Top ? 3.5 : 2.0) * diagonal);

  // Fit the projected corners: the projection of a box in front of the eye lies inside the
  // projection of its corners' hull.
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  c.near_depth = 1e300;
  c.far_depth = 0;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 p((k & 1) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 4) ? box.hi.z : box.lo.z);
    const glm::dvec3 v = p - c.eye;
    const double depth = -glm::dot(v, c.back);
    const double x = glm::dot(v, c.right) / depth, y = glm::dot(v, c.up) / depth;
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    c.near_depth = std::min(c.near_depth, depth), c.far_depth = std::max(c.far_depth, depth);
  }
  const double w = std::max(x1 - x0, 1e-6), h = std::max(y1 - y0, 1e-6);
  c.scale = std::min(area.w * (1 - 2 * margin) / w, area.h * (1 - 2 * margin) / h);
  c.offset_x = area.x + area.w / 2 - c.scale * (x0 + x1) / 2;
  c.offset_y = area.y + area.h / 2 + c.scale * (y0 + y1) / 2;
  return c;
}

ScreenPoint camera_project(const Camera& camera, const glm::dvec3& p) {
  const glm::dvec3 v = p - camera.eye;
  ScreenPoint s;
  s.depth = std::max(-glm::dot(v, camera.back), 1e-6);
  s.x = camera.offset_x + camera.scale * glm::dot(v, camera.right) / s.depth;
  s.y = camera.offset_y - camera.scale * glm::dot(v, camera.up) / s.depth;
  return s;
}

}  // namespace gmg::render
