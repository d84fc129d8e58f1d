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

// Throws Interrupted once Ctrl-C, a TERM or a HUP came (engine/core/interrupt.h): the job ends
// through the error path, so ffmpeg is stopped and the temporary video removed.
void check_interrupt(const std::string& output) { throw_if_interrupted(output, "no video written"); }

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

}  // namespace

const std::vector<std::string> kVideoExtensions = {".mp4", ".mkv", ".mov"};

RenderSummary render_video(const RenderInputs& in, const RenderOptions& options) {
  check_output_file({"", in.output}, kVideoExtensions);
  // The partial videos of renders that were killed (SIGKILL cannot be caught) go now.
  remove_stale_temporaries(fs::path(in.output).parent_path().string(), kVideoExtensions);
  const InterruptFlag interrupt;
  const std::string ffmpeg = find_executable(options.ffmpeg);
  if (ffmpeg.empty())
    throw Error(options.ffmpeg + ": not found" + (options.ffmpeg.find('/') == std::string::npos ? " on PATH" : "") +
                ": gmg render encodes with the ffmpeg tool (Debian: apt-get install ffmpeg)");
  const Scene scene = scene_load(in, options);

  EncoderSettings e;
  e.ffmpeg = ffmpeg;
  // Beside the output, so the final rename stays on one file system, and named as every
  // temporary of gmg is, so a later render removes it should this one be killed.
  e.output = temporary_name_for(in.output);
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
