// Everything `gmg render` draws, prepared once (figures, the fixed camera, the background with
// its floor, captions, markers), and the drawing of one frame. render.h encodes the frames.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <cairo.h>

#include "engine/core/enum_names.h"
#include "engine/render/camera.h"
#include "engine/render/figure.h"
#include "engine/render/overlay.h"
#include "text/transcript.h"

namespace gmg::render {

struct RenderInputs {
  std::string motion;      // BVH or SMPL-X .npz (required); the video has its frame count and rate
  std::string skeleton;    // BVH skeleton template of .npz motions (engine/motion/npz.h); "" = none
  std::string audio;       // audio muxed into the video (and its onsets marked, with a report); "" = silent
  std::string transcript;  // words shown as captions; "" = none
  text::TranscriptFormat transcript_format = text::TranscriptFormat::Auto;
  std::string tier;     // TextGrid tier of the captions; "" = the default
  std::string report;   // reenactment report: junction markers, and onset markers with the audio; "" = none
  std::string compare;  // a second BVH drawn to the right, same camera; "" = none
  std::string output;   // the video (.mp4, .mkv or .mov)
};

// What is drawn over the figures: nothing (the figures on their floor, for a paper figure), the
// event strip (with a --report) and the panels' labels, or also the badges that light up on each
// event. Captions come with a transcript whatever the overlay.
enum class Overlay : std::uint8_t { None, Strip, All };
inline constexpr EnumName<Overlay> kOverlayNames[] = {
    {Overlay::None, "none"}, {Overlay::Strip, "strip"}, {Overlay::All, "all"}};

struct RenderOptions {
  View view = View::Front;
  Overlay overlay = Overlay::All;
  // The part of the motion drawn, in seconds: frames [round(from_s fps), round(to_s fps)); to_s < 0
  // = to the end. The audio is cut to the same range; captions and markers keep their times.
  double from_s = 0, to_s = -1;
  int width = 640, height = 480;  // pixels per figure; even, 160x120 to 3840x2160
  std::string ffmpeg = "ffmpeg";  // the tool, found on PATH unless it contains a '/'
  int crf = 20;                   // x264 quality: lower is better, 0 is lossless
  std::string preset = "veryfast";
};

// One figure and where it is drawn.
struct Panel {
  Figure figure;
  FigureStyle style;
  Camera camera;  // the same view for every panel, shifted to its area
  Rect area;      // the panel, pixels
  std::string label;
};

struct Scene {
  double fps = 30;
  int frame_count = 0;
  int width = 0, height = 0;  // the whole picture
  std::vector<Panel> panels;  // the motion, then the --compare one
  std::vector<Caption> captions;
  Rect caption_area;
  double font_size = 16;
  bool show_markers = false;                                         // a report was given: its events are known
  bool show_strip = false, show_badges = false, show_labels = true;  // what the overlay draws
  Markers markers;
  Rect strip;
  std::shared_ptr<cairo_surface_t> background;  // sky, floors, labels
  double audio_s = -1;                          // the WAV's duration; -1 without audio
  std::vector<std::string> notes;               // warnings for the user (lengths that differ, ...)
};

// Throws gmg::Error "--size: WxH is not an even size from 160x120 to 3840x2160" for a size out of
// range (scene_load checks it too; the command line checks it first, as a usage error).
void check_size(const RenderOptions& o);

// Reads the inputs and prepares the picture. gmg::Error naming the file for any unreadable or
// invalid input, an empty motion, or a size out of range.
Scene scene_load(const RenderInputs& in, const RenderOptions& options);

// Draws frame `frame` (0 <= frame < frame_count) over the whole picture. A figure whose motion
// is shorter than the first holds its last frame.
void scene_draw(const Scene& scene, int frame, cairo_t* cr);

// A Cairo picture of the scene's size (32-bit pixels, native byte order).
class Canvas {
 public:
  Canvas(int width, int height);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;
  cairo_t* context() const { return cr_; }
  // The pixels, after flushing what was drawn.
  const unsigned char* pixels() const;
  int stride() const { return cairo_image_surface_get_stride(surface_); }
  int width() const { return cairo_image_surface_get_width(surface_); }
  int height() const { return cairo_image_surface_get_height(surface_); }
  // Writes the picture as a PNG, atomically (engine/core/files.h); gmg::Error naming the file.
  void write_png(const std::string& path) const;

 private:
  cairo_surface_t* surface_;
  cairo_t* cr_;
};

}  // namespace gmg::render
