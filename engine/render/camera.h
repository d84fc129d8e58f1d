// The fixed camera of `gmg render`: a perspective view of the figure from the front, the side or
// above, placed once for the whole clip so that every joint of every frame stays in the picture
// (a camera that follows the figure would hide the root's own motion).
//
// World space is the BVH's, Y up, in centimetres. Screen space is pixels, x right, y down.
#pragma once

#include <limits>
#include <string>

#include <glm/glm.hpp>

namespace gmg::render {

enum class View { Front, Side, Top };

// "front", "side" or "top"; gmg::Error listing the choices otherwise.
View parse_view(const std::string& name);

// An axis-aligned box in world space; empty until a point is added.
struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  void add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void add(const Box& b) {
    if (!b.empty()) add(b.lo), add(b.hi);
  }
  bool empty() const { return !(lo.x <= hi.x); }
};

// A rectangle of the picture, in pixels.
struct Rect {
  double x = 0, y = 0, w = 0, h = 0;
};

struct ScreenPoint {
  double x = 0, y = 0;  // pixels
  double depth = 0;     // distance in front of the camera along its view direction (cm, > 0)
};

struct Camera {
  glm::dvec3 eye{0.0};
  glm::dvec3 right{1, 0, 0}, up{0, 1, 0}, back{0, 0, 1};  // orthonormal; back points at the eye
  double scale = 1, offset_x = 0, offset_y = 0;           // pixels = offset + scale * (x, -y) / depth
  double near_depth = 1, far_depth = 2;                   // depth range of the framed box (fog)
};

// A camera framing `box` inside `area` with `margin` (a fraction of the area on each side).
// `facing` is the person's forward direction (only its part along the floor counts; +Z when it
// has none). Front looks at the person's face from slightly above, so their left hand is on the
// right of the picture; Side looks at their left side (they face left); Top looks straight down
// with their front towards the bottom of the picture. The perspective is mild (the eye is two box
// diagonals away, three and a half from above), enough for near parts to look larger. Requires a non-empty box.
Camera camera_fit(const Box& box, const glm::dvec3& facing, View view, const Rect& area, double margin = 0.05);

ScreenPoint camera_project(const Camera& camera, const glm::dvec3& p);

// Pixels covered by a world length (cm) seen at `depth`.
inline double camera_pixels(const Camera& camera, double length_cm, double depth) {
  return camera.scale * length_cm / depth;
}

}  // namespace gmg::render
