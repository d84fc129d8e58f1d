// What `gmg render` draws over the figures: the current words as captions, and markers on the
// speech's onsets and the path's junctions (a scrolling strip with a playhead, and a badge that
// lights up on each one).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <cairo.h>

#include "engine/render/camera.h"
#include "text/transcript.h"

namespace gmg::render {

// One caption: consecutive words shown together, from `show` until `hide` (seconds).
struct Caption {
  double show = 0, hide = 0;
  std::vector<text::Word> words;
};

// Groups words into captions as subtitles do: a new caption after a pause longer than 0.7 s,
// when the line would be wider than max_width (width() measures a text) or longer than 4 s.
// A caption shows from 0.15 s before its first word until 1 s after its last, but never overlaps
// the next one.
std::vector<Caption> make_captions(const std::vector<text::Word>& words, double max_width,
                                   const std::function<double(const std::string&)>& width);

// The caption showing at time t, or null.
const Caption* caption_at(const std::vector<Caption>& captions, double t);

// The caption on a dark band across `area`: words already spoken white, the word being spoken
// yellow and bold, the words to come grey.
void draw_caption(cairo_t* cr, const Caption& caption, double t, const Rect& area, double font_size);

struct Markers {
  std::vector<double> onsets_s;     // speech onsets (audio/onset.h)
  std::vector<double> junctions_s;  // where the reenacted path jumps (report_facts.h)
  // [from, to) seconds kept from an earlier output, planned afresh and pinned (report_facts.h);
  // empty for a reenactment made without --keep or --pin.
  std::vector<std::pair<double, double>> kept_s, planned_s, pinned_s;
};

// How long a badge stays lit after its event (s).
inline constexpr double kBadgeSeconds = 0.2;

// A strip showing the events of the 6 s around t, scrolling past a playhead in the middle:
// onsets as short green ticks, junctions as tall red ones; along its bottom edge a band grey where
// the motion is kept, amber where it is planned and violet where it is pinned.
void draw_marker_strip(cairo_t* cr, const Markers& markers, double t, const Rect& strip);

// Badges in the top right corner of `panel`, lit for kBadgeSeconds after an event: "onset"
// (green) and "junction" (red).
void draw_marker_badges(cairo_t* cr, const Markers& markers, double t, const Rect& panel, double font_size);

// True when some event of `times` lies in [t - kBadgeSeconds, t].
bool badge_lit(const std::vector<double>& times, double t);

}  // namespace gmg::render
