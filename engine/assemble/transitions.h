// Natural transitions (SPEC "Blending (paper 4.2.4) and natural transitions (ours)"): the output
// is read from the source at continuous source time (engine/assemble/timeline.h); at every
// transition, a junction that did not continue or an unnatural edge taken inside a path, the
// pose and velocity offset between where the output was heading and the new source is carried
// over and decays with a critically damped spring (engine/assemble/inertialize.h). A continuous
// junction is left untouched.
//
// The root joint's horizontal position is anchored: a new piece continues from where the output
// was, instead of jumping to (or gliding towards) the capture spot it was recorded at. The anchor
// relaxes slowly toward the capture's own position (half-life root_halflife_s), so the speaker
// stays near the reference's standing area without a visible drift. Facing and height are
// inertialized like every other channel: continuous at the switch, back to the capture within a
// second. The vertical axis is Y (BVH's convention, and that of every dataset read here).
#pragma once

#include <vector>

#include "engine/assemble/params.h"
#include "engine/assemble/timeline.h"
#include "engine/motion/capture_facts.h"
#include "engine/motion/capture_runs.h"
#include "engine/motion/motion.h"

namespace gmg {

// `runs`: the source's capture runs; `facts`: its capture facts (engine/motion/capture_facts.h,
// known), which a graph keeps, so that the source is read only at the frames the pieces play.
// Returns exactly the pieces' total length in frames, in the source's skeleton and fps.
// params.halflife_s > 0.
// `anchor_feet` (joints, e.g. the two foot ends of engine/motion/body_layers.h): at a transition the
// anchor keeps their horizontal mean where it was instead of the root, and the root's own offset
// decays with the legs': the hips shift over the transition while planted feet stay (the lower body
// of a layered reenactment, which changes stance only with both feet planted). Empty: the root.
Motion assemble_inertialized(const Motion& source, const CaptureRuns& runs, const CaptureFacts& facts,
                             const std::vector<PathPiece>& pieces, const BlendParams& params,
                             const std::vector<int>& anchor_feet = {}, const BeatAlignment* beats = nullptr);

// The same for a source described by `continues[f]` (source frame f is naturally followed by
// f + 1), its capture facts computed over every frame first.
Motion assemble_inertialized(const Motion& source, const std::vector<char>& continues,
                             const std::vector<PathPiece>& pieces, const BlendParams& params);

}  // namespace gmg
