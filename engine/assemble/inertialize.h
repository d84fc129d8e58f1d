// Inertialization (Bollo's, in the spring form of Holden's "dead blending" and motion matching
// code): at a transition the difference between where the output was heading and the new
// source, in pose and velocity, becomes an offset that a critically damped spring takes to zero.
// The output's position and velocity stay continuous at the switch and the new source takes over
// smoothly, instead of a cross-fade squeezing the jump into a few frames.
#pragma once

#include <glm/glm.hpp>

namespace gmg {

// The damping y of the critically damped spring x(t) = (x0 + (v0 + y x0) t) e^(-y t) for a given
// half-life, as Holden's code defines it: y = 2 ln 2 / halflife. An offset that starts at rest is
// at 50 % after 1.21 half-lives and under 1 % after 4.79 (0.96 s at the default 0.2 s).
double spring_damping(double halflife_frames);

// Advances an offset x with velocity v (per frame) by dt frames of the critically damped spring
// with damping y. Exact for any dt.
void spring_decay(glm::dvec3& x, glm::dvec3& v, double y, double dt);

// Frames until an offset that starts at rest falls below `fraction` of its size: the smallest t
// with (1 + y t) e^(-y t) <= fraction. For fraction 0.01 that is 6.64 / y, 4.79 half-lives.
double spring_settle_frames(double y, double fraction);

}  // namespace gmg
