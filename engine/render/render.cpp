#include "engine/render/render.h"

#include <unistd.h>

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

void check_output(const std::string& path) {
  if (!ends_with_ci(path, ".mp4") && !ends_with_ci(path, ".mkv") && !ends_with_ci(path, ".mov"))
    throw Error(path + ": the video must be a .mp4, .mkv or .mov file");
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw Error(path + ": the folder " + parent.string() + " does not exist");
}

// Throws once Ctrl-C or a TERM came (engine/core/interrupt.h): the job ends through the error
// path, so the temporary video is removed rather than left behind.
void check_interrupt(const std::string& output) {
  if (InterruptFlag::raised()) throw Error(output + ": interrupted; no video written");
}

// A signal after a successful finish() changes nothing: the video is complete.
void encode(const Scene& scene, const EncoderSettings& settings) {
  check_interrupt(settings.name);
  VideoEncoder encoder(settings);
  Canvas canvas(scene.width, scene.height);
  try {
    for (int f = 0; f < scene.frame_count; ++f) {
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

// Beside the output, so the final rename stays on one file system; same extension, so ffmpeg
// picks the same container.
std::string temporary_twin(const std::string& path) {
  const fs::path p(path);
  const fs::path name = p.stem().string() + ".tmp" + std::to_string(::getpid()) + p.extension().string();
  return (p.parent_path() / name).string();
}

}  // namespace

RenderSummary render_video(const RenderInputs& in, const RenderOptions& options) {
  check_output(in.output);
  const InterruptFlag interrupt;
  const std::string ffmpeg = find_executable(options.ffmpeg);
  if (ffmpeg.empty())
    throw Error(options.ffmpeg + ": not found" + (options.ffmpeg.find('/') == std::string::npos ? " on PATH" : "") +
                ": gmg render encodes with the ffmpeg tool (Debian: apt-get install ffmpeg)");
  const Scene scene = scene_load(in, options);

  EncoderSettings e;
  e.ffmpeg = ffmpeg;
  e.output = temporary_twin(in.output);
  e.name = in.output;
  e.audio = in.audio;
  e.width = scene.width;
  e.height = scene.height;
  e.fps = scene.fps;
  e.crf = options.crf;
  e.preset = options.preset;
  encode(scene, e);
  rename_into_place(e.output, in.output);
  RenderSummary r;
  r.frames = scene.frame_count;
  r.fps = scene.fps;
  r.width = scene.width;
  r.height = scene.height;
  r.audio_s = scene.audio_s;
  r.notes = scene.notes;
  return r;
}

}  // namespace gmg::render
