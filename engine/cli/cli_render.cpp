// `gmg render`: a video of a motion with its speech, captions and markers.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "engine/cli/cli_common.h"
#include "engine/core/enum_names.h"
#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/render/render.h"

namespace gmg {
namespace {

struct RenderArgs {
  render::RenderInputs inputs;
  render::RenderOptions options;
  std::string view = "front", size = "640x480", format = "auto", overlay = "all";
  std::optional<double> from, to, still;
};

void parse_size(const std::string& text, render::RenderOptions& o) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
    throw UsageError("--size: '" + text + "' is not WIDTHxHEIGHT (e.g. 640x480)");
  o.width = w;
  o.height = h;
  try {
    render::check_size(o);
  } catch (const Error& e) {
    throw UsageError(e.what());  // an option out of range, not an input's problem
  }
}

void run_render(RenderArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  if (a.still)
    check_output_extensions({{"-o", a.inputs.output, {".png"}}}, " (--still draws one frame as a .png)");
  else
    check_output_extensions({{"-o", a.inputs.output, render::kVideoExtensions}},
                            ends_with_ci(a.inputs.output, ".png") ? " (a .png is one frame: --still SECONDS)" : "");
  a.options.view = render::parse_view(a.view);
  parse_size(a.size, a.options);
  a.inputs.transcript_format = text::parse_transcript_format(a.format);
  a.options.overlay = *enum_from_name(render::kOverlayNames, a.overlay);
  if (a.still && (a.from || a.to)) throw UsageError("render: --still draws one frame; it takes no --from or --to");
  if (a.from) a.options.from_s = *a.from;
  if (a.to) a.options.to_s = *a.to;
  if (a.to && !(*a.to > a.options.from_s))
    throw UsageError("render: --to " + format_number(*a.to) + " must be after --from " +
                     format_number(a.options.from_s));
  const render::RenderSummary r =
      a.still ? render::render_still(a.inputs, a.options, *a.still) : render::render_video(a.inputs, a.options);
  print_warnings(r.notes);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (a.still) {
    std::cout << "wrote " << a.inputs.output << ": the frame at " << format_number(*a.still) << " s, " << r.width << "x"
              << r.height << "\n";
    return;
  }
  std::cout << "wrote " << a.inputs.output << ": " << r.frames << " frames at " << r.fps << " fps, " << r.width << "x"
            << r.height;
  if (r.audio_s >= 0) std::cout << ", audio " << r.audio_s << " s";
  std::cout << " (" << static_cast<int>(took * 10) / 10.0 << " s)\n";
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "draw a motion as a video with its speech (needs the ffmpeg tool)");
  auto a = std::make_shared<RenderArgs>();
  render::RenderInputs& in = a->inputs;
  cmd->add_option("motion", in.motion, "the motion to draw: BVH, or SMPL-X .npz with --skeleton")->required();
  cmd->add_option("--skeleton", in.skeleton, "BVH whose hierarchy gives .npz motions their skeleton");
  cmd->add_option("--audio", in.audio, "the speech (WAV, FLAC, MP3, ...), muxed into the video");
  cmd->add_option("--transcript", in.transcript, "its transcript (.tsv, .TextGrid, .json): captions");
  transcript_format_check(
      cmd->add_option("--transcript-format", a->format, "auto, tsv, textgrid or json (Google, Whisper, WhisperX)"));
  cmd->add_option("--tier", in.tier, "TextGrid tier of the captions (default: 'words', else the only interval tier)");
  cmd->add_option("--report", in.report, "the reenactment report: mark path junctions (and onsets, with --audio)");
  cmd->add_option("--compare", in.compare, "a second motion drawn beside the first, same camera (e.g. the truth)");
  cmd->add_option("--view", a->view, "camera: front, side or top")
      ->check(CLI::IsMember({"front", "side", "top"}))
      ->capture_default_str();
  cmd->add_option("--size", a->size, "pixels per figure, WIDTHxHEIGHT (even)")->capture_default_str();
  cmd->add_option("--ffmpeg", a->options.ffmpeg, "the ffmpeg tool")->capture_default_str();
  seconds_number(cmd->add_option("--from", a->from, "draw from this time on (seconds; the audio is cut to the range)"));
  seconds_number(cmd->add_option("--to", a->to, "draw up to this time (seconds)"));
  seconds_number(cmd->add_option("--still", a->still, "draw only the frame at this time (seconds) into a .png -o"));
  cmd->add_option("--overlay", a->overlay,
                  "what is drawn over the figures: all (event strip and badges with --report, labels), strip (no "
                  "badges) or none (the figures only)")
      ->check(CLI::IsMember({"none", "strip", "all"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", in.output, "the video to write (.mp4, .mkv or .mov), or a .png with --still")
      ->required();
  cmd->callback([a] { run_render(*a); });
}

}  // namespace gmg
