#include "engine/render/overlay.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "engine/core/math.h"

namespace gmg::render {
namespace {

constexpr double kPause = 0.7, kMaxCaptionSeconds = 4.0, kLead = 0.15, kLinger = 1.0, kStripSeconds = 6.0;

std::string joined(const std::vector<text::Word>& words) {
  std::string s;
  for (const text::Word& w : words) s += (s.empty() ? "" : " ") + w.text;
  return s;
}

void rounded_rect(cairo_t* cr, double x, double y, double w, double h, double r) {
  cairo_new_sub_path(cr);
  cairo_arc(cr, x + w - r, y + r, r, -kPi / 2, 0);
  cairo_arc(cr, x + w - r, y + h - r, r, 0, kPi / 2);
  cairo_arc(cr, x + r, y + h - r, r, kPi / 2, kPi);
  cairo_arc(cr, x + r, y + r, r, kPi, 3 * kPi / 2);
  cairo_close_path(cr);
}

void set_font(cairo_t* cr, bool bold, double size) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double text_advance(cairo_t* cr, const std::string& s) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  return e.x_advance;
}

void badge(cairo_t* cr, double right, double top, const char* label, bool lit, const glm::dvec3& color, double size) {
  set_font(cr, true, size);
  const double w = text_advance(cr, label) + 2.2 * size, h = 1.6 * size, x = right - w;
  rounded_rect(cr, x, top, w, h, h / 2);
  if (lit)
    cairo_set_source_rgb(cr, color.r, color.g, color.b);
  else
    cairo_set_source_rgba(cr, 0.5, 0.5, 0.5, 0.18);
  cairo_fill(cr);
  cairo_arc(cr, x + 0.8 * size, top + h / 2, 0.3 * size, 0, kTwoPi);
  cairo_set_source_rgb(cr, lit ? 1.0 : 0.55, lit ? 1.0 : 0.55, lit ? 1.0 : 0.55);
  cairo_fill(cr);
  cairo_move_to(cr, x + 1.4 * size, top + h / 2 + 0.36 * size);
  cairo_show_text(cr, label);
}

}  // namespace

std::vector<Caption> make_captions(const std::vector<text::Word>& words, double max_width,
                                   const std::function<double(const std::string&)>& width) {
  std::vector<Caption> out;
  for (const text::Word& w : words) {
    bool fresh = out.empty();
    if (!fresh) {
      const Caption& c = out.back();
      std::vector<text::Word> longer = c.words;
      longer.push_back(w);
      fresh = w.start - c.words.back().end > kPause || w.end - c.words.front().start > kMaxCaptionSeconds ||
              width(joined(longer)) > max_width;
    }
    if (fresh) out.push_back({});
    out.back().words.push_back(w);
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    Caption& c = out[i];
    c.show = std::max(0.0, c.words.front().start - kLead);
    double last_end = 0;
    for (const text::Word& w : c.words) last_end = std::max(last_end, w.end);
    c.hide = last_end + kLinger;
    if (i + 1 < out.size()) c.hide = std::min(c.hide, std::max(last_end, out[i + 1].words.front().start - kLead));
  }
  return out;
}

const Caption* caption_at(const std::vector<Caption>& captions, double t) {
  for (const Caption& c : captions)
    if (t >= c.show && t < c.hide) return &c;
  return nullptr;
}

void draw_caption(cairo_t* cr, const Caption& caption, double t, const Rect& area, double font_size) {
  cairo_save(cr);
  std::vector<double> advances;
  double total = 0;
  for (const text::Word& w : caption.words) {
    set_font(cr, t >= w.start && t < w.end, font_size);
    advances.push_back(text_advance(cr, w.text + " "));
    total += advances.back();
  }
  set_font(cr, false, font_size);
  total -= text_advance(cr, " ");
  const double h = 1.7 * font_size, y = area.y + (area.h - h) / 2;
  double x = area.x + (area.w - total) / 2;
  rounded_rect(cr, x - 0.6 * font_size, y, total + 1.2 * font_size, h, 0.3 * font_size);
  cairo_set_source_rgba(cr, 0.08, 0.09, 0.11, 0.78);
  cairo_fill(cr);
  for (std::size_t i = 0; i < caption.words.size(); ++i) {
    const text::Word& w = caption.words[i];
    const bool now = t >= w.start && t < w.end, spoken = t >= w.end;
    set_font(cr, now, font_size);
    if (now)
      cairo_set_source_rgb(cr, 1.0, 0.86, 0.25);
    else if (spoken)
      cairo_set_source_rgb(cr, 0.97, 0.97, 0.97);
    else
      cairo_set_source_rgb(cr, 0.58, 0.60, 0.64);
    cairo_move_to(cr, x, y + 1.15 * font_size);
    cairo_show_text(cr, w.text.c_str());
    x += advances[i];
  }
  cairo_restore(cr);
}

bool badge_lit(const std::vector<double>& times, double t) {
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  return it != times.begin() && t - *(it - 1) <= kBadgeSeconds;
}

void draw_marker_strip(cairo_t* cr, const Markers& markers, double t, const Rect& strip) {
  cairo_save(cr);
  cairo_rectangle(cr, strip.x, strip.y, strip.w, strip.h);
  cairo_set_source_rgb(cr, 0.16, 0.17, 0.2);
  cairo_fill_preserve(cr);
  cairo_clip(cr);
  const double px_per_s = strip.w / kStripSeconds, mid = strip.x + strip.w / 2;
  auto ticks = [&](const std::vector<double>& times, double top, double bottom, double width) {
    const auto lo = std::lower_bound(times.begin(), times.end(), t - kStripSeconds / 2 - 1);
    for (auto it = lo; it != times.end() && *it <= t + kStripSeconds / 2 + 1; ++it) {
      const double x = mid + (*it - t) * px_per_s;
      cairo_rectangle(cr, x - width / 2, top, width, bottom - top);
    }
    cairo_fill(cr);
  };
  auto band = [&](const std::vector<std::pair<double, double>>& spans, double r, double g, double b) {
    cairo_set_source_rgb(cr, r, g, b);
    for (const auto& [from, to] : spans)
      if (to >= t - kStripSeconds / 2 - 1 && from <= t + kStripSeconds / 2 + 1)
        cairo_rectangle(cr, mid + (from - t) * px_per_s, strip.y + strip.h * 0.85, (to - from) * px_per_s,
                        strip.h * 0.15);
    cairo_fill(cr);
  };
  band(markers.kept_s, 0.55, 0.57, 0.62);
  band(markers.planned_s, 0.95, 0.7, 0.2);
  band(markers.pinned_s, 0.62, 0.4, 0.95);
  cairo_set_source_rgb(cr, 0.25, 0.85, 0.4);
  ticks(markers.onsets_s, strip.y + strip.h * 0.45, strip.y + strip.h, 2.0);
  cairo_set_source_rgb(cr, 0.95, 0.22, 0.2);
  ticks(markers.junctions_s, strip.y, strip.y + strip.h, 3.0);
  // One-second ticks along the top edge show the scrolling even where there are no events.
  cairo_set_source_rgba(cr, 1, 1, 1, 0.35);
  std::vector<double> seconds;
  for (double s = std::floor(t - kStripSeconds / 2); s <= t + kStripSeconds / 2 + 1; s += 1.0) seconds.push_back(s);
  ticks(seconds, strip.y, strip.y + strip.h * 0.2, 1.0);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_rectangle(cr, mid - 1, strip.y, 2, strip.h);
  cairo_fill(cr);
  cairo_restore(cr);
}

void draw_marker_badges(cairo_t* cr, const Markers& markers, double t, const Rect& panel, double font_size) {
  cairo_save(cr);
  const double right = panel.x + panel.w - 0.6 * font_size, top = panel.y + 0.5 * font_size;
  badge(cr, right, top, "junction", badge_lit(markers.junctions_s, t), {0.88, 0.16, 0.14}, font_size);
  badge(cr, right, top + 2.0 * font_size, "onset", badge_lit(markers.onsets_s, t), {0.15, 0.62, 0.3}, font_size);
  cairo_restore(cr);
}

}  // namespace gmg::render
