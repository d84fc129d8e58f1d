#include "engine/render/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "audio/audio_file.h"
#include "audio/onset.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"
#include "engine/motion/motion_file.h"
#include "engine/motion/up_axis.h"
#include "engine/pipeline/report_facts.h"

namespace gmg::render {
namespace {

constexpr glm::dvec3 kMainColor{0.30, 0.50, 0.82}, kCompareColor{0.90, 0.55, 0.22};
constexpr glm::dvec3 kSkyTop{0.93, 0.94, 0.96}, kSkyBottom{0.80, 0.83, 0.87};

Figure load_figure(const std::string& path, const std::string& skeleton) {
  const Motion m = motion_read_y_up(path, skeleton);  // drawn standing, whatever the file's up axis
  if (m.frame_count == 0) throw Error(path + ": the motion has no frames to render");
  return figure_from_motion(m);
}

std::string format_seconds(double s) { return format_number(std::round(s * 100) / 100) + " s"; }

// Speech onsets as the reenactment found them: with its min_onset_strength when the report
// records one.
std::vector<double> speech_onsets(const audio::Audio& sound, const ReportFacts& facts) {
  audio::OnsetParams params;
  if (facts.parameters.is_object() && facts.parameters.contains("min_onset_strength") &&
      facts.parameters["min_onset_strength"].is_number())
    params.min_onset_strength = facts.parameters["min_onset_strength"].get<double>();
  return audio::detect_onsets(sound, params).onset_times();
}

void read_speech(const RenderInputs& in, Scene& s) {
  audio::Audio sound;
  if (!in.audio.empty()) {
    sound = audio::read_audio(in.audio, &s.notes);
    s.audio_s = sound.duration();
    if (std::abs(s.audio_s - s.frame_count / s.fps) > 1.0)
      s.notes.push_back(in.audio + " lasts " + format_seconds(s.audio_s) + " and " + in.motion + " " +
                        format_seconds(s.frame_count / s.fps) + ": the video keeps both lengths");
  }
  if (!in.report.empty()) {
    const ReportFacts facts = read_report_facts(in.report, s.fps);
    if (facts.frames >= 0 && facts.frames != s.frame_count)
      s.notes.push_back(in.report + " describes " + std::to_string(facts.frames) + " frames but " + in.motion +
                        " has " + std::to_string(s.frame_count) + ": is it the report of another motion?");
    s.show_markers = true;
    s.markers.junctions_s = facts.junctions_s;
    s.markers.kept_s = facts.kept_s;
    s.markers.planned_s = facts.planned_s;
    s.markers.pinned_s = facts.pinned_s;
    if (!in.audio.empty())
      s.markers.onsets_s = speech_onsets(sound, facts);
    else
      s.notes.push_back("no --audio: only junctions are marked, not onsets");
  }
}

// Lays out the panels (left to right) and the bands for the strip and the captions, and places
// one camera framing every figure over every frame.
void lay_out(const RenderOptions& o, Scene& s) {
  const double w = o.width, h = o.height;
  s.font_size = std::max(11.0, h * 0.036);
  s.show_strip = s.show_markers && o.overlay != Overlay::None;
  s.show_badges = s.show_markers && o.overlay == Overlay::All;
  s.show_labels = o.overlay != Overlay::None;
  const double top = (s.show_strip ? h * 0.06 : 0.0) + (s.show_labels ? s.font_size * 1.8 : 0.0);
  const double bottom = s.captions.empty() ? 0.0 : h * 0.13;
  s.strip = {0, 0, w * static_cast<double>(s.panels.size()), s.show_strip ? h * 0.06 : 0.0};
  s.caption_area = {0, h - bottom, w * static_cast<double>(s.panels.size()), bottom};
  Box box;
  for (const Panel& p : s.panels) box.add(figure_box(p.figure));
  const glm::dvec3 facing = figure_facing(s.panels.front().figure);
  for (std::size_t k = 0; k < s.panels.size(); ++k) {
    Panel& p = s.panels[k];
    p.area = {w * static_cast<double>(k), 0, w, h};
    p.camera = camera_fit(box, facing, o.view, {p.area.x, top, w, h - top - bottom});
    p.style.floor_y = box.lo.y;
  }
}

void draw_background(Scene& s, const Box& box) {
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, s.width, s.height);
  cairo_t* cr = cairo_create(surface);
  cairo_pattern_t* sky = cairo_pattern_create_linear(0, 0, 0, s.height);
  cairo_pattern_add_color_stop_rgb(sky, 0, kSkyTop.r, kSkyTop.g, kSkyTop.b);
  cairo_pattern_add_color_stop_rgb(sky, 1, kSkyBottom.r, kSkyBottom.g, kSkyBottom.b);
  cairo_set_source(cr, sky);
  cairo_paint(cr);
  cairo_pattern_destroy(sky);
  for (const Panel& p : s.panels) {
    cairo_save(cr);
    cairo_rectangle(cr, p.area.x, p.area.y, p.area.w, p.area.h);
    cairo_clip(cr);
    draw_floor(cr, p.camera, box, p.style.floor_y);
    if (s.show_labels) {
      cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
      cairo_set_font_size(cr, s.font_size * 0.9);
      cairo_set_source_rgb(cr, 0.25, 0.27, 0.3);
      cairo_move_to(cr, p.area.x + 0.6 * s.font_size, s.strip.h + 1.3 * s.font_size);
      cairo_show_text(cr, p.label.c_str());
    }
    cairo_restore(cr);
    if (p.area.x > 0) {
      cairo_set_source_rgb(cr, 0.35, 0.36, 0.4);
      cairo_rectangle(cr, p.area.x - 1, 0, 2, s.height);
      cairo_fill(cr);
    }
  }
  cairo_destroy(cr);
  s.background = std::shared_ptr<cairo_surface_t>(surface, cairo_surface_destroy);
}

void make_captions_for(const std::vector<text::Word>& words, Scene& s) {
  cairo_surface_t* scratch = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
  cairo_t* cr = cairo_create(scratch);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  const double font = std::max(12.0, s.height * 0.05);
  cairo_set_font_size(cr, font);
  s.captions = make_captions(words, s.width - 3.0 * font, [cr](const std::string& text) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, text.c_str(), &e);
    return e.x_advance;
  });
  cairo_destroy(cr);
  cairo_surface_destroy(scratch);
}

}  // namespace

Scene scene_load(const RenderInputs& in, const RenderOptions& options) {
  check_size(options);
  Scene s;
  Panel main;
  main.figure = load_figure(in.motion, in.skeleton);
  main.style.color = kMainColor;
  main.label = std::filesystem::path(in.motion).filename().string();
  s.fps = main.figure.fps;
  s.frame_count = main.figure.frame_count;
  s.panels.push_back(std::move(main));
  if (!in.compare.empty()) {
    Panel other;
    other.figure = load_figure(in.compare, in.skeleton);
    other.style.color = kCompareColor;
    other.label = std::filesystem::path(in.compare).filename().string();
    const double a = s.frame_count / s.fps, b = other.figure.frame_count / other.figure.fps;
    if (std::abs(a - b) > 1.0 / s.fps)
      s.notes.push_back(in.compare + " lasts " + format_seconds(b) + " and " + in.motion + " " + format_seconds(a) +
                        (b < a ? ": it holds its last frame" : ": its end is not shown"));
    s.panels.push_back(std::move(other));
  }
  s.width = options.width * static_cast<int>(s.panels.size());
  s.height = options.height;
  read_speech(in, s);
  if (!in.transcript.empty()) make_captions_for(text::read_transcript(in.transcript, in.transcript_format, in.tier), s);
  lay_out(options, s);
  Box box;
  for (const Panel& p : s.panels) box.add(figure_box(p.figure));
  draw_background(s, box);
  return s;
}

void scene_draw(const Scene& s, int frame, cairo_t* cr) {
  const double t = frame / s.fps;
  cairo_save(cr);
  cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
  cairo_set_source_surface(cr, s.background.get(), 0, 0);
  cairo_paint(cr);
  cairo_restore(cr);
  for (const Panel& p : s.panels) {
    const int k = std::clamp(static_cast<int>(std::lround(t * p.figure.fps)), 0, p.figure.frame_count - 1);
    cairo_save(cr);
    cairo_rectangle(cr, p.area.x, p.area.y, p.area.w, p.area.h);
    cairo_clip(cr);
    draw_figure(cr, p.camera, p.figure, k, p.style);
    cairo_restore(cr);
  }
  if (const Caption* c = caption_at(s.captions, t))
    draw_caption(cr, *c, t, s.caption_area, std::max(12.0, s.height * 0.05));
  if (s.show_strip) draw_marker_strip(cr, s.markers, t, s.strip);
  if (s.show_badges) {
    Rect badges = s.panels.front().area;
    badges.y = s.strip.h;
    draw_marker_badges(cr, s.markers, t, badges, s.font_size * 0.8);
  }
}

Canvas::Canvas(int width, int height)
    : surface_(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height)), cr_(cairo_create(surface_)) {}

Canvas::~Canvas() {
  cairo_destroy(cr_);
  cairo_surface_destroy(surface_);
}

void Canvas::write_png(const std::string& path) const {
  cairo_surface_flush(surface_);
  write_file_atomically(
      path,
      [&](std::ostream& os) {
        const cairo_status_t status = cairo_surface_write_to_png_stream(
            surface_,
            [](void* closure, const unsigned char* data, unsigned int length) {
              auto* out = static_cast<std::ostream*>(closure);
              out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
              return *out ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
            },
            &os);
        if (status != CAIRO_STATUS_SUCCESS)
          throw Error(path + ": cannot write the PNG (" + cairo_status_to_string(status) + ")");
      },
      true);
}

const unsigned char* Canvas::pixels() const {
  cairo_surface_flush(surface_);
  return cairo_image_surface_get_data(surface_);
}

void check_size(const RenderOptions& o) {
  if (o.width < 160 || o.height < 120 || o.width > 3840 || o.height > 2160 || o.width % 2 || o.height % 2)
    throw Error("--size: " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                " is not an even size from 160x120 to 3840x2160");
}

}  // namespace gmg::render
