// The figure `gmg render` draws for a motion: its bones as tapered capsules, the head as a
// sphere, shaded as lit from the upper left, fogged with depth and casting a shadow on the floor.
//
// Which bones are drawn and how thick comes from the joint names, so the same rules serve the
// Mixamo/GENEA/ZEGGS ("LeftForeArm"), SMPL-X/BEAT2 ("left_elbow") and Talking With Hands
// ("b_l_forearm") skeletons: face joints (eyes, jaw, teeth, tongue), helper end points ("...End",
// "..._null", leaf "p_..." joints) and a world root above the body root are left out.
#pragma once

#include <string>
#include <vector>

#include <cairo.h>
#include <Eigen/Core>

#include "engine/motion/motion.h"
#include "engine/render/camera.h"

namespace gmg::render {

struct Bone {
  int a = 0, b = 0;  // point indices; a is the parent end
};

struct Figure {
  double fps = 30;
  int frame_count = 0;
  // World positions in cm, frame_count x 3 * point count: the joints (BVH order), then one point
  // per End Site (in joint order), then the nose when there is a head.
  Eigen::MatrixXd points;
  std::vector<double> radius_cm;  // per point: the capsule radius at that point
  std::vector<int> side;          // per point: +1 the person's left, -1 right, 0 the middle
  std::vector<Bone> bones;        // drawn bones
  int head = -1, head_base = -1;  // the head joint and its parent; -1 when there is none
  int nose = -1;                  // a point on the front of the head (it turns with the head); -1 without a head
  double head_radius_cm = 10.0;
};

// The figure of a motion, in centimetres whatever the file's unit (metres are detected as for
// the metrics: engine/metrics/evaluate.h length_unit_to_cm).
Figure figure_from_motion(const Motion& m);

// Capsule radius of a joint by its name (cm): fingers thin, torso thick.
double joint_radius_cm(const std::string& name);

// +1 for a joint of the person's left ("Left...", "left_...", "b_l_..."), -1 for the right, 0.
int joint_side(const std::string& name);

// The centre of the head sphere at a frame.
glm::dvec3 figure_head_center(const Figure& f, int frame);

glm::dvec3 figure_point(const Figure& f, int frame, int point);

// Everything drawn, over all frames, capsule radii included.
Box figure_box(const Figure& f);

// The person's mean forward direction on the floor: perpendicular to the line from their right
// to their left joints (+Z when the skeleton names no sides).
glm::dvec3 figure_facing(const Figure& f);

struct FigureStyle {
  glm::dvec3 color{0.30, 0.50, 0.82};  // RGB 0..1; the left side is drawn lighter, the right darker
  glm::dvec3 fog{0.86, 0.88, 0.91};    // what far parts fade towards (the background)
  double floor_y = 0;                  // world height of the floor (cm), for the shadow
};

// Draws the figure at `frame`: shadow first, then bones and head far to near.
void draw_figure(cairo_t* cr, const Camera& camera, const Figure& f, int frame, const FigureStyle& style);

// The floor: a tiled square around the box, drawn in perspective (the picture's background).
void draw_floor(cairo_t* cr, const Camera& camera, const Box& box, double floor_y);

}  // namespace gmg::render
