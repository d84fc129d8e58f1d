// `gmg render`: a video of a motion with its speech, for looking at a result (GENEA-style
// evaluations are done on such videos). The figure is drawn by scene.h, the frames are encoded
// by the ffmpeg tool (encoder.h).
//
// Contract: the video has exactly the BVH's frame count at its frame rate; the audio stream,
// when given, keeps the WAV's duration (neither is cut to the other). The file appears complete
// or not at all: ffmpeg writes a temporary file beside it, renamed at the end, and any failure
// (an unreadable input, no ffmpeg, ffmpeg failing) removes it.
#pragma once

#include <string>
#include <vector>

#include "engine/render/scene.h"

namespace gmg::render {

struct RenderSummary {
  int frames = 0;
  double fps = 30;
  int width = 0, height = 0;
  double audio_s = -1;  // -1: no audio stream
  std::vector<std::string> notes;
};

// The containers render_video writes, by extension: {".mp4", ".mkv", ".mov"}.
extern const std::vector<std::string> kVideoExtensions;

// gmg::Error "path: what" for a missing or invalid input, an output that is not .mp4, .mkv or
// .mov or cannot be written (check_output_file), a range (options.from_s, to_s) that holds no frame
// of the motion, no ffmpeg (options.ffmpeg not found), or ffmpeg failing; Interrupted on SIGINT,
// SIGTERM or SIGHUP (ffmpeg stopped, nothing written). With a range the video has exactly the
// range's frames and the audio is cut to it. First it removes the temporary videos that renders
// killed by SIGKILL left in the output's folder (remove_stale_temporaries), and ffmpeg dies with
// this process, whatever kills it.
RenderSummary render_video(const RenderInputs& in, const RenderOptions& options);

// One frame, the one shown at `at_s` seconds (round(at_s fps)), as a PNG of the video's size
// (in.output must end in .png); no ffmpeg is needed. gmg::Error as render_video, and for a time
// outside the motion.
RenderSummary render_still(const RenderInputs& in, const RenderOptions& options, double at_s);

}  // namespace gmg::render
