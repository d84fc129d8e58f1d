// gmg render: the video's streams (ffprobe), its pixels (decoded by ffmpeg), the errors that
// leave no file, and the drawing of a scene in memory. The video tests skip with a message when
// the ffmpeg tools are absent (the scene's parts on their own: test_render_scene.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <thread>

#include <cairo.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "audio/wav.h"
#include "engine/cli/cli.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/motion/bvh.h"
#include "engine/render/encoder.h"
#include "engine/render/render.h"
#include "engine/synth/synth.h"
#include "tests/cli/cli_run.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"

extern char** environ;

namespace gmg {
namespace {

namespace fs = std::filesystem;
using render::RenderInputs;
using render::RenderOptions;
using testing::error_of;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

bool have_ffmpeg_tools() {
  return !render::find_executable("ffmpeg").empty() && !render::find_executable("ffprobe").empty();
}

#define GMG_REQUIRE_FFMPEG()                                                                \
  do {                                                                                      \
    if (!have_ffmpeg_tools()) GTEST_SKIP() << "ffmpeg or ffprobe is not on PATH: skipping"; \
  } while (0)

// Standard output of a shell command (the paths here are temporary folders without quotes).
std::string command_output(const std::string& command, int* status = nullptr) {
  std::string out;
  FILE* p = ::popen(command.c_str(), "r");
  if (p == nullptr) return out;
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, p)) > 0) out.append(buffer, n);
  const int rc = ::pclose(p);
  if (status) *status = rc;
  return out;
}

nlohmann::json probe(const std::string& video) {
  const std::string out = command_output(
      "ffprobe -v error -count_frames -show_entries "
      "stream=codec_type,width,height,r_frame_rate,nb_read_frames,duration -of json '" +
      video + "'");
  return nlohmann::json::parse(out);
}

std::vector<nlohmann::json> streams_of(const nlohmann::json& probed, const std::string& type) {
  std::vector<nlohmann::json> out;
  for (const auto& s : probed["streams"])
    if (s["codec_type"] == type) out.push_back(s);
  return out;
}

// Every frame of the video as RGB bytes, decoded by ffmpeg.
std::vector<std::string> decode_frames(const std::string& video, int width, int height) {
  const std::string all = command_output("ffmpeg -v error -i '" + video + "' -f rawvideo -pix_fmt rgb24 -");
  const std::size_t size = static_cast<std::size_t>(width) * height * 3;
  std::vector<std::string> frames;
  for (std::size_t at = 0; at + size <= all.size(); at += size) frames.push_back(all.substr(at, size));
  return frames;
}

// Pixels (of 3 or 4 bytes) where some channel differs by more than `threshold` levels.
int differing_pixels(const std::string& a, const std::string& b, int bytes_per_pixel, int threshold = 24) {
  int n = 0;
  for (std::size_t i = 0; i + 2 < a.size() && i + 2 < b.size(); i += bytes_per_pixel)
    for (int c = 0; c < 3; ++c)
      if (std::abs(static_cast<int>(static_cast<unsigned char>(a[i + c])) -
                   static_cast<int>(static_cast<unsigned char>(b[i + c]))) > threshold) {
        ++n;
        break;
      }
  return n;
}

// A WAV of exactly `samples` samples at `rate` (a quiet tone), so its duration is known exactly.
void write_tone(const std::string& path, int samples, int rate) {
  audio::Audio a;
  a.sample_rate = rate;
  for (int i = 0; i < samples; ++i) a.samples.push_back(0.2f * static_cast<float>(std::sin(i * 0.05)));
  audio::write_wav_pcm16(path, a);
}

using testing::CliRun;

CliRun run_cli(std::vector<std::string> args) { return testing::run_gmg(std::move(args)); }

std::vector<std::string> folder_listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class RenderVideo : public ::testing::Test {
 protected:
  void SetUp() override {
    SynthSpec spec;
    spec.duration_s = 2.0;  // 60 frames at 30 fps
    spec.seed = 5;
    synth_write(synth_speaker(spec), dir.path().string(), "clip");
  }
  RenderInputs inputs(const std::string& output) const {
    RenderInputs in;
    in.motion = dir.file("clip.bvh");
    in.output = dir.file(output);
    return in;
  }
  static RenderOptions small() {
    RenderOptions o;
    o.width = 320;
    o.height = 240;
    return o;
  }
  gmg::testing::TempDir dir;
};

TEST_F(RenderVideo, OneVideoStreamOfTheMotionsFramesAndOneAudioStreamOfTheWavsDuration) {
  GMG_REQUIRE_FFMPEG();
  // Audio shorter and longer than the 2 s motion: neither stream is cut to the other.
  for (const int samples : {19680, 43360}) {  // 1.23 s and 2.71 s at 16 kHz
    write_tone(dir.file("tone.wav"), samples, 16000);
    RenderInputs in = inputs("out.mp4");
    in.audio = dir.file("tone.wav");
    render::render_video(in, small());
    const nlohmann::json p = probe(in.output);
    const auto video = streams_of(p, "video"), sound = streams_of(p, "audio");
    ASSERT_EQ(video.size(), 1u) << p.dump();
    ASSERT_EQ(sound.size(), 1u) << p.dump();
    EXPECT_EQ(video[0]["nb_read_frames"], "60");
    EXPECT_EQ(video[0]["r_frame_rate"], "30/1");
    EXPECT_EQ(video[0]["width"], 320);
    EXPECT_EQ(video[0]["height"], 240);
    EXPECT_NEAR(std::stod(sound[0]["duration"].get<std::string>()), samples / 16000.0, 1.0 / 30) << samples;
  }
}

TEST_F(RenderVideo, FrameExactAtTheBvhsOwnRateAndSilentWithoutAudio) {
  GMG_REQUIRE_FFMPEG();
  SynthSpec spec;
  spec.duration_s = 1.6;
  spec.fps = 25;  // 40 frames
  synth_write(synth_speaker(spec), dir.path().string(), "at25");
  RenderInputs in = inputs("at25.mkv");
  in.motion = dir.file("at25.bvh");
  render::render_video(in, small());
  const nlohmann::json p = probe(in.output);
  const auto video = streams_of(p, "video");
  ASSERT_EQ(video.size(), 1u);
  EXPECT_EQ(video[0]["nb_read_frames"], "40");
  EXPECT_EQ(video[0]["r_frame_rate"], "25/1");
  EXPECT_TRUE(streams_of(p, "audio").empty());
  EXPECT_EQ(decode_frames(in.output, 320, 240).size(), 40u);
}

TEST_F(RenderVideo, FramesASecondApartDifferAndAStillMotionGivesIdenticalFrames) {
  GMG_REQUIRE_FFMPEG();
  render::render_video(inputs("moving.mp4"), small());
  const std::vector<std::string> moving = decode_frames(dir.file("moving.mp4"), 320, 240);
  ASSERT_EQ(moving.size(), 60u);
  // Without captions or markers only the figure (and its shadow) can change.
  EXPECT_GT(differing_pixels(moving[0], moving[30], 3), 100);
  EXPECT_GT(differing_pixels(moving[29], moving[59], 3), 100);

  Motion still = bvh_read(dir.file("clip.bvh"));
  for (int f = 1; f < still.frame_count; ++f) motion_copy_frame(still, 0, still, f);
  still.euler_hints.clear();
  bvh_write(dir.file("still.bvh"), still);
  RenderInputs in = inputs("still.mp4");
  in.motion = dir.file("still.bvh");
  // Lossless (crf 0): the pipeline itself adds nothing that changes from frame to frame.
  RenderOptions lossless = small();
  lossless.crf = 0;
  render::render_video(in, lossless);
  std::vector<std::string> frames = decode_frames(in.output, 320, 240);
  ASSERT_EQ(frames.size(), 60u);
  for (std::size_t f = 1; f < frames.size(); ++f) EXPECT_TRUE(frames[f] == frames[0]) << "frame " << f;
  // At the default quality x264 refines its first picture over the next few, so decoded frames
  // differ by codec noise (up to about 25 levels); a figure that moves changes pixels by far more.
  render::render_video(in, small());
  frames = decode_frames(in.output, 320, 240);
  ASSERT_EQ(frames.size(), 60u);
  for (std::size_t f = 1; f < frames.size(); ++f) EXPECT_EQ(differing_pixels(frames[f], frames[0], 3, 40), 0) << f;
  EXPECT_GT(differing_pixels(moving[0], moving[30], 3, 40), 100);
}

TEST_F(RenderVideo, CompareDrawsBothMotionsSideBySideForTheFirstMotionsFrames) {
  GMG_REQUIRE_FFMPEG();
  SynthSpec spec;
  spec.duration_s = 1.0;
  spec.seed = 9;
  synth_write(synth_speaker(spec), dir.path().string(), "short");
  RenderInputs in = inputs("pair.mp4");
  in.compare = dir.file("short.bvh");
  const render::RenderSummary r = render::render_video(in, small());
  ASSERT_EQ(r.notes.size(), 1u);  // the other motion is shorter: it holds its last frame
  EXPECT_TRUE(contains(r.notes[0], "holds its last frame")) << r.notes[0];
  const auto video = streams_of(probe(in.output), "video");
  ASSERT_EQ(video.size(), 1u);
  EXPECT_EQ(video[0]["width"], 640);
  EXPECT_EQ(video[0]["nb_read_frames"], "60");
}

TEST_F(RenderVideo, MissingInputsAreClearErrorsAndLeaveNoFile) {
  GMG_REQUIRE_FFMPEG();  // its absence is reported first
  const std::vector<std::string> before = folder_listing(dir.path());
  const std::string out = dir.file("out.mp4"), bvh = dir.file("clip.bvh"), wav = dir.file("clip.wav");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"render", bvh, "--audio", dir.file("nope.wav"), "-o", out}, dir.file("nope.wav")},
      {{"render", dir.file("nope.bvh"), "-o", out}, dir.file("nope.bvh")},
      {{"render", bvh, "--transcript", dir.file("nope.tsv"), "-o", out}, dir.file("nope.tsv")},
      {{"render", bvh, "--audio", wav, "--report", dir.file("nope.json"), "-o", out}, dir.file("nope.json")},
  };
  for (const auto& [args, missing] : cases) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.code, 1) << missing;
    EXPECT_TRUE(contains(r.err, "gmg: error: " + missing + ": cannot open")) << r.err;
    EXPECT_EQ(folder_listing(dir.path()), before) << missing;
  }
}

TEST_F(RenderVideo, NoFfmpegIsAClearError) {
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", dir.file("no_such_folder").c_str(), 1);
  const CliRun r = run_cli({"render", dir.file("clip.bvh"), "-o", dir.file("out.mp4")});
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "gmg: error: ffmpeg: not found on PATH")) << r.err;
  EXPECT_TRUE(contains(r.err, "apt-get install ffmpeg")) << r.err;
  EXPECT_FALSE(fs::exists(dir.file("out.mp4")));
}

TEST_F(RenderVideo, AFailingFfmpegIsReportedWithItsMessageAndLeavesNoFile) {
  const std::string fake = dir.file("fake_ffmpeg");
  gmg::testing::write_text(fake, "#!/bin/sh\necho 'Unknown encoder libx264' >&2\nexit 1\n");
  fs::permissions(fake, fs::perms::owner_all);
  const std::vector<std::string> before = folder_listing(dir.path());
  RenderOptions o = small();
  o.ffmpeg = fake;
  try {
    render::render_video(inputs("out.mp4"), o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), dir.file("out.mp4") + ": ffmpeg")) << e.what();
    EXPECT_TRUE(contains(e.what(), "Unknown encoder libx264")) << e.what();
  }
  EXPECT_EQ(folder_listing(dir.path()), before);
}

TEST_F(RenderVideo, AnInterruptedRenderLeavesNoFile) {
  GMG_REQUIRE_FFMPEG();
  SynthSpec spec;
  spec.duration_s = 30;  // seconds of rendering: time to interrupt it
  synth_write(synth_speaker(spec), dir.path().string(), "long");
  const std::vector<std::string> before = folder_listing(dir.path());
  gmg::testing::TempDir logs;
  const std::string bvh = dir.file("long.bvh"), out = dir.file("out.mp4"), err = logs.file("err.txt");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<std::string> args = {GMG_BINARY, "render", bvh, "-o", out};
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // gmg's own temporary files (ffmpeg's messages) go to a folder of their own, to be looked at.
  gmg::testing::TempDir tmp;
  const char* saved_tmpdir = std::getenv("TMPDIR");
  const std::string saved = saved_tmpdir ? saved_tmpdir : "";
  ::setenv("TMPDIR", tmp.path().c_str(), 1);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, GMG_BINARY, &actions, nullptr, argv.data(), environ);
  if (saved_tmpdir) {
    ::setenv("TMPDIR", saved.c_str(), 1);
  } else {
    ::unsetenv("TMPDIR");
  }
  ASSERT_EQ(spawned, 0);
  posix_spawn_file_actions_destroy(&actions);
  // Interrupt once ffmpeg has started writing its temporary file.
  bool writing = false;
  for (int i = 0; i < 1000 && !writing; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    for (const std::string& name : folder_listing(dir.path())) writing = writing || contains(name, ".tmp");
  }
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(writing);
  // The interrupt contract (engine/core/interrupt.h): ffmpeg stopped, then gmg ends by the signal.
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_TRUE(contains(read_file_bytes(err), "gmg: error: " + out + ": interrupted")) << read_file_bytes(err);
  EXPECT_EQ(folder_listing(dir.path()), before);
  EXPECT_TRUE(folder_listing(tmp.path()).empty()) << "a temporary file of gmg's outlived it";
}

TEST_F(RenderVideo, BadOutputNamesAndSizesAreRefused) {
  RenderOptions o = small();
  EXPECT_THROW(render::render_video(inputs("out.gif"), o), Error);
  EXPECT_THROW(render::render_video(inputs("no_folder/out.mp4"), o), Error);
  o.width = 321;
  RenderInputs in = inputs("out.mp4");
  EXPECT_THROW(render::scene_load(in, o), Error);
  const CliRun r = run_cli({"render", dir.file("clip.bvh"), "--size", "big", "-o", dir.file("out.mp4")});
  EXPECT_EQ(r.code, 2);  // a usage error
  EXPECT_TRUE(contains(r.err, "--size")) << r.err;
  EXPECT_FALSE(fs::exists(dir.file("out.mp4")));
}

// ---- In memory: no ffmpeg needed -------------------------------------------------------------

std::string draw(const render::Scene& s, int frame) {
  render::Canvas canvas(s.width, s.height);
  render::scene_draw(s, frame, canvas.context());
  return std::string(reinterpret_cast<const char*>(canvas.pixels()),
                     static_cast<std::size_t>(canvas.stride()) * canvas.height());
}

TEST_F(RenderVideo, DrawnFramesOfAStillMotionAreIdenticalAndOfAMovingOneDiffer) {
  const render::Scene moving = render::scene_load(inputs("x.mp4"), small());
  EXPECT_GT(differing_pixels(draw(moving, 0), draw(moving, 30), 4), 100);
  Motion still = bvh_read(dir.file("clip.bvh"));
  for (int f = 1; f < still.frame_count; ++f) motion_copy_frame(still, 10, still, f);
  motion_copy_frame(still, 10, still, 0);
  still.euler_hints.clear();
  bvh_write(dir.file("still.bvh"), still);
  RenderInputs in = inputs("x.mp4");
  in.motion = dir.file("still.bvh");
  const render::Scene s = render::scene_load(in, small());
  EXPECT_EQ(draw(s, 0), draw(s, 31));
  EXPECT_EQ(draw(s, 0), draw(s, 59));
}

// Count of clearly red pixels (the junction badge) inside a rectangle of a drawn frame.
int red_pixels(const std::string& frame, int stride, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const auto* p = reinterpret_cast<const unsigned char*>(frame.data()) + static_cast<std::size_t>(y) * stride +
                      4 * static_cast<std::size_t>(x);
      if (p[2] > 180 && p[1] < 80 && p[0] < 80) ++n;  // B, G, R in memory
    }
  return n;
}

TEST_F(RenderVideo, TheJunctionBadgeLightsJustAfterAJunctionOnly) {
  // Graph frames 0..29 then 100..129: one junction, at output frame 30 (1.0 s).
  gmg::testing::write_text(dir.file("report.json"), R"({"frames": 60, "totals": {"failures": 0},
    "subsequences": [{"start_frame": 0, "target_length": 30, "graph_ranges": [[0, 29]]},
                     {"start_frame": 30, "target_length": 30, "graph_ranges": [[100, 129]]}]})");
  RenderInputs in = inputs("x.mp4");
  in.report = dir.file("report.json");
  const render::Scene s = render::scene_load(in, small());
  ASSERT_EQ(s.markers.junctions_s.size(), 1u);
  EXPECT_DOUBLE_EQ(s.markers.junctions_s[0], 1.0);
  ASSERT_EQ(s.notes.size(), 1u);  // no audio, so no onsets
  const int stride = 320 * 4;
  // The badge sits in the top right quarter; the strip above it is excluded.
  auto badge_red = [&](int frame) { return red_pixels(draw(s, frame), stride, 160, 20, 320, 60); };
  EXPECT_GT(badge_red(31), 50);  // 0.03 s after the junction
  EXPECT_EQ(badge_red(20), 0);
  EXPECT_EQ(badge_red(40), 0);  // 0.33 s after: off again
}

// ---- a time range, a still frame, the overlay ------------------------------------------------

TEST_F(RenderVideo, ARangeHasExactlyItsFramesTheFullVideosPixelsAndItsPartOfTheAudio) {
  GMG_REQUIRE_FFMPEG();
  write_tone(dir.file("tone.wav"), 32000, 16000);  // 2 s, as long as the motion
  RenderOptions lossless = small();
  lossless.crf = 0;
  RenderInputs full = inputs("full.mp4");
  render::render_video(full, lossless);
  RenderInputs in = inputs("range.mp4");
  in.audio = dir.file("tone.wav");
  RenderOptions o = lossless;
  o.from_s = 0.5;
  o.to_s = 1.5;
  const render::RenderSummary r = render::render_video(in, o);
  EXPECT_EQ(r.frames, 30);
  const nlohmann::json p = probe(in.output);
  const auto video = streams_of(p, "video"), sound = streams_of(p, "audio");
  ASSERT_EQ(video.size(), 1u);
  ASSERT_EQ(sound.size(), 1u);
  EXPECT_EQ(video[0]["nb_read_frames"], "30");
  EXPECT_NEAR(std::stod(sound[0]["duration"].get<std::string>()), 1.0, 1.0 / 30);
  // Frame k of the range is frame 15 + k of the whole video.
  const std::vector<std::string> all = decode_frames(full.output, 320, 240), part = decode_frames(in.output, 320, 240);
  ASSERT_EQ(all.size(), 60u);
  ASSERT_EQ(part.size(), 30u);
  for (std::size_t k : {0u, 14u, 29u}) EXPECT_EQ(differing_pixels(part[k], all[15 + k], 3, 2), 0) << k;
  EXPECT_GT(differing_pixels(part[0], all[0], 3), 100);
  // --to past the end stops at the end; a range after the end holds nothing and writes nothing.
  o.from_s = 1.0;
  o.to_s = 9.0;
  EXPECT_EQ(render::render_video(inputs("tail.mp4"), o).frames, 30);
  o.from_s = 5.0;
  o.to_s = -1;
  EXPECT_TRUE(contains(error_of([&] { render::render_video(inputs("none.mp4"), o); }), "holds no frame of the motion"));
  EXPECT_FALSE(fs::exists(dir.file("none.mp4")));
}

// The pixels of a PNG as Cairo draws them (native 32-bit words), and its size.
std::string png_pixels(const std::string& path, int& width, int& height) {
  cairo_surface_t* png = cairo_image_surface_create_from_png(path.c_str());
  std::string out;
  width = height = 0;
  if (cairo_surface_status(png) == CAIRO_STATUS_SUCCESS) {
    width = cairo_image_surface_get_width(png);
    height = cairo_image_surface_get_height(png);
    render::Canvas canvas(width, height);
    cairo_set_source_surface(canvas.context(), png, 0, 0);
    cairo_set_operator(canvas.context(), CAIRO_OPERATOR_SOURCE);
    cairo_paint(canvas.context());
    out.assign(reinterpret_cast<const char*>(canvas.pixels()), static_cast<std::size_t>(canvas.stride()) * height);
  }
  cairo_surface_destroy(png);
  return out;
}

TEST_F(RenderVideo, AStillIsOnePngOfTheVideosSizeShowingTheFrameAtItsTime) {
  const render::Scene scene = render::scene_load(inputs("x.mp4"), small());
  for (const double t : {0.2, 1.0}) {
    RenderInputs in = inputs("still.png");
    const render::RenderSummary r = render::render_still(in, small(), t);
    EXPECT_EQ(r.frames, 1);
    int w = 0, h = 0;
    const std::string pixels = png_pixels(in.output, w, h);
    EXPECT_EQ(w, 320);
    EXPECT_EQ(h, 240);
    // Exactly the frame the video shows at t (frame round(t * 30)).
    EXPECT_EQ(pixels, draw(scene, static_cast<int>(std::lround(t * 30)))) << t;
    fs::rename(in.output, dir.file("still_" + std::to_string(static_cast<int>(t * 10)) + ".png"));
  }
  int w = 0, h = 0;
  EXPECT_GT(differing_pixels(png_pixels(dir.file("still_2.png"), w, h), png_pixels(dir.file("still_10.png"), w, h), 4),
            100);
  // Outside the motion, or not a .png: an error and no file.
  EXPECT_TRUE(contains(error_of([&] { render::render_still(inputs("late.png"), small(), 2.5); }),
                       "--still 2.5 s is outside the motion"));
  EXPECT_TRUE(contains(error_of([&] { render::render_still(inputs("still.mp4"), small(), 1.0); }),
                       "a still frame is written as a .png file"));
  EXPECT_FALSE(fs::exists(dir.file("late.png")));
  EXPECT_FALSE(fs::exists(dir.file("still.mp4")));
}

TEST_F(RenderVideo, TheOverlayShowsStripAndBadgesOnlyTheStripOrNothing) {
  // Graph frames 0..29 then 100..129: one junction at output frame 30 (1.0 s).
  gmg::testing::write_text(dir.file("report.json"), R"({"frames": 60, "totals": {"failures": 0},
    "subsequences": [{"start_frame": 0, "target_length": 30, "graph_ranges": [[0, 29]]},
                     {"start_frame": 30, "target_length": 30, "graph_ranges": [[100, 129]]}]})");
  RenderInputs with_report = inputs("x.mp4");
  with_report.report = dir.file("report.json");
  auto scene = [&](render::Overlay overlay, bool report) {
    RenderOptions o = small();
    o.overlay = overlay;
    return render::scene_load(report ? with_report : inputs("x.mp4"), o);
  };
  const int stride = 320 * 4;
  const std::string all = draw(scene(render::Overlay::All, true), 31);
  const std::string strip = draw(scene(render::Overlay::Strip, true), 31);
  const std::string none = draw(scene(render::Overlay::None, true), 31);
  EXPECT_GT(red_pixels(all, stride, 160, 20, 320, 60), 50);  // the junction badge
  EXPECT_EQ(red_pixels(strip, stride, 160, 20, 320, 60), 0);
  EXPECT_GT(red_pixels(strip, stride, 0, 0, 320, 15), 0);  // the strip's junction tick
  EXPECT_EQ(red_pixels(none, stride, 0, 0, 320, 240), 0);
  // Nothing at all: the report changes no pixel, and the motion's file name is not written.
  EXPECT_EQ(none, draw(scene(render::Overlay::None, false), 31));
  EXPECT_NE(draw(scene(render::Overlay::All, false), 31), draw(scene(render::Overlay::None, false), 31));
}

TEST_F(RenderVideo, RangeStillAndOverlayOptionsOfTheCommand) {
  const CliRun bad =
      run_cli({"render", dir.file("clip.bvh"), "--still", "1", "--from", "0.5", "-o", dir.file("s.png")});
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_TRUE(contains(bad.err, "--still draws one frame"));
  EXPECT_EQ(run_cli({"render", dir.file("clip.bvh"), "--overlay", "some", "-o", dir.file("v.mp4")}).code, 2);
  const CliRun backwards =
      run_cli({"render", dir.file("clip.bvh"), "--from", "1", "--to", "0.5", "-o", dir.file("v.mp4")});
  EXPECT_EQ(backwards.code, 2) << backwards.err;
  const CliRun still =
      run_cli({"render", dir.file("clip.bvh"), "--still", "0.5", "--overlay", "none", "-o", dir.file("s.png")});
  EXPECT_EQ(still.code, 0) << still.err;
  EXPECT_TRUE(contains(still.out, "the frame at 0.5 s, 320x240") || contains(still.out, "the frame at 0.5 s, 640x480"))
      << still.out;
  EXPECT_TRUE(fs::exists(dir.file("s.png")));
  const CliRun png = run_cli({"render", dir.file("clip.bvh"), "-o", dir.file("v.png")});
  EXPECT_EQ(png.code, 2);  // a wrong extension is the command line's
  EXPECT_TRUE(contains(png.err, "a .png is one frame: --still SECONDS")) << png.err;
}

TEST_F(RenderVideo, TheCameraFramesEveryJointOfEveryFrameInEveryView) {
  for (const render::View view : {render::View::Front, render::View::Side, render::View::Top}) {
    RenderOptions o = small();
    o.view = view;
    const render::Scene s = render::scene_load(inputs("x.mp4"), o);
    const render::Panel& p = s.panels.front();
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (int f = 0; f < p.figure.frame_count; ++f)
      for (Eigen::Index j = 0; j < p.figure.points.cols() / 3; ++j) {
        const render::ScreenPoint q = render::camera_project(p.camera, render::figure_point(p.figure, f, j));
        x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
      }
    EXPECT_GE(x0, 0);
    EXPECT_LE(x1, 320);
    EXPECT_GE(y0, 0);
    EXPECT_LE(y1, 240);
    // Framed, not lost in the middle: the figure spans a good part of the picture one way.
    EXPECT_GT(std::max((x1 - x0) / 320, (y1 - y0) / 240), 0.5) << static_cast<int>(view);
  }
}

}  // namespace
}  // namespace gmg
