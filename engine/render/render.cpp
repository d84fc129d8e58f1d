#include "engine/render/render.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/interrupt.h"
#include "engine/core/strings.h"
#include "engine/render/encoder.h"

namespace gmg::render {
namespace {

namespace fs = std::filesystem;

// Frames [first, end) of the scene that options' range holds.
struct FrameRange {
  int first = 0, end = 0;
};

FrameRange frame_range(const Scene& scene, const RenderOptions& o, const std::string& motion) {
  const double length_s = scene.frame_count / scene.fps;
  if (!(o.from_s >= 0) || (o.to_s >= 0 && !(o.to_s > o.from_s)))
    throw Error("--from " + format_number(o.from_s) + " --to " + format_number(o.to_s) +
                ": the range must start at 0 s or later and end after it starts");
  FrameRange r;
  r.first = static_cast<int>(std::lround(std::min(o.from_s, length_s) * scene.fps));
  r.end = o.to_s < 0 ? scene.frame_count : static_cast<int>(std::lround(std::min(o.to_s, length_s) * scene.fps));
  if (r.first >= r.end)
    throw Error(motion + ": the range " + format_number(o.from_s) + " s to " +
                (o.to_s < 0 ? std::string("the end") : format_number(o.to_s) + " s") +
                " holds no frame of the motion (" + format_number(length_s) + " s)");
  return r;
}

// Throws Interrupted once Ctrl-C, a TERM or a HUP came (engine/core/interrupt.h): the job ends
// through the error path, so ffmpeg is stopped and the temporary video removed.
void check_interrupt(const std::string& output) { throw_if_interrupted(output, "no video written"); }

// A signal after a successful finish() changes nothing: the video is complete.
void encode(const Scene& scene, const FrameRange& range, const EncoderSettings& settings) {
  check_interrupt(settings.name);
  VideoEncoder encoder(settings);
  Canvas canvas(scene.width, scene.height);
  try {
    for (int f = range.first; f < range.end; ++f) {
      check_interrupt(settings.name);
      scene_draw(scene, f, canvas.context());
      encoder.write_frame(canvas.pixels(), canvas.stride());
    }
    check_interrupt(settings.name);
    encoder.finish();
  } catch (const Error&) {
    check_interrupt(settings.name);  // ffmpeg got the Ctrl-C too: say why it stopped
    throw;
  }
}

}  // namespace

const std::vector<std::string> kVideoExtensions = {".mp4", ".mkv", ".mov"};

RenderSummary render_video(const RenderInputs& in, const RenderOptions& options) {
  try {
    check_output_file({"", in.output}, kVideoExtensions);
  } catch (const Error& e) {
    if (!ends_with_ci(in.output, ".png")) throw;
    throw Error(std::string(e.what()) + " (a .png is one frame: --still SECONDS)");
  }
  // The partial videos of renders that were killed (SIGKILL cannot be caught) go now.
  remove_stale_temporaries(fs::path(in.output).parent_path().string(), kVideoExtensions);
  const InterruptFlag interrupt;
  const std::string ffmpeg = find_executable(options.ffmpeg);
  if (ffmpeg.empty())
    throw Error(options.ffmpeg + ": not found" + (options.ffmpeg.find('/') == std::string::npos ? " on PATH" : "") +
                ": gmg render encodes with the ffmpeg tool (Debian: apt-get install ffmpeg)");
  const Scene scene = scene_load(in, options);
  const FrameRange range = frame_range(scene, options, in.motion);

  EncoderSettings e;
  e.ffmpeg = ffmpeg;
  // Beside the output, so the final rename stays on one file system, and named as every
  // temporary of gmg is, so a later render removes it should this one be killed.
  e.output = temporary_name_for(in.output);
  e.name = in.output;
  e.audio = in.audio;
  if (range.first > 0 || range.end < scene.frame_count) {
    e.audio_from_s = range.first / scene.fps;
    e.audio_for_s = (range.end - range.first) / scene.fps;
  }
  e.width = scene.width;
  e.height = scene.height;
  e.fps = scene.fps;
  e.crf = options.crf;
  e.preset = options.preset;
  encode(scene, range, e);
  rename_into_place(e.output, in.output);
  RenderSummary r;
  r.frames = range.end - range.first;
  r.fps = scene.fps;
  r.width = scene.width;
  r.height = scene.height;
  r.audio_s = scene.audio_s < 0 || e.audio_for_s < 0
                  ? scene.audio_s
                  : std::max(0.0, std::min(e.audio_for_s, scene.audio_s - e.audio_from_s));
  r.notes = scene.notes;
  return r;
}

RenderSummary render_still(const RenderInputs& in, const RenderOptions& options, double at_s) {
  if (!ends_with_ci(in.output, ".png")) throw Error(in.output + ": a still frame is written as a .png file");
  check_output_file({"", in.output}, {".png"});  // the folder exists and can be written
  const Scene scene = scene_load(in, options);
  const int frame = static_cast<int>(std::lround(at_s * scene.fps));
  if (!(at_s >= 0) || frame >= scene.frame_count)
    throw Error(in.motion + ": --still " + format_number(at_s) + " s is outside the motion (0 to " +
                format_number((scene.frame_count - 1) / scene.fps) + " s)");
  Canvas canvas(scene.width, scene.height);
  scene_draw(scene, frame, canvas.context());
  canvas.write_png(in.output);
  RenderSummary r;
  r.frames = 1;
  r.fps = scene.fps;
  r.width = scene.width;
  r.height = scene.height;
  r.notes = scene.notes;
  return r;
}

}  // namespace gmg::render
