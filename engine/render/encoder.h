// The video encoder of `gmg render`: the ffmpeg command-line tool, fed raw frames on a pipe.
//
// Why the tool rather than FFmpeg's libraries: it is one Debian package (ffmpeg), its encoders
// and muxers are used exactly as a user would on the command line, and muxing the WAV as AAC
// needs no resampling or packet code here. Frames go in as Cairo's native 32-bit pixels, so
// nothing is converted on this side.
#pragma once

#include <sys/types.h>
#include <string>

namespace gmg::render {

// The full path of an executable: `name` itself when it contains a '/', else the first match on
// PATH. "" when there is none.
std::string find_executable(const std::string& name);

// A frame rate as a fraction ffmpeg keeps exactly: whole rates as n/1, the NTSC family as
// n*1000/1001, others to a thousandth. Requires fps > 0.
struct Rational {
  long num = 30, den = 1;
};
Rational fps_rational(double fps);

struct EncoderSettings {
  std::string ffmpeg;         // full path (find_executable)
  std::string output;         // the file ffmpeg writes (its extension picks the container)
  std::string name;           // the file as errors name it (the user's -o; output is its temporary twin)
  std::string audio;          // WAV muxed as AAC; "" = no audio stream
  double audio_from_s = 0;    // the audio from this time on (a range of the motion) ...
  double audio_for_s = -1;    // ... for this long; -1 = to its end
  int width = 0, height = 0;  // even
  double fps = 30;
  int crf = 20;                     // x264 quality: lower is better, 0 is lossless
  std::string preset = "veryfast";  // x264 speed
};

// Runs ffmpeg for the life of the object. Every frame becomes exactly one video frame at the
// given rate (no frame is dropped or duplicated, and the audio, which keeps its own length, does
// not cut the video). On destruction without finish() ffmpeg is stopped and `output` removed;
// ffmpeg is killed by the kernel should this process die (PR_SET_PDEATHSIG), and `output` is
// registered for removal on a signal. The container follows `name`'s extension (.mkv Matroska,
// .mov QuickTime, else MP4), so `output` may have any name.
class VideoEncoder {
 public:
  explicit VideoEncoder(const EncoderSettings& settings);
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  // One frame of width * height 32-bit pixels (Cairo RGB24/ARGB32, native byte order), rows
  // `stride` bytes apart. gmg::Error with ffmpeg's message when it has stopped.
  void write_frame(const unsigned char* pixels, int stride);

  // Ends the stream and waits for ffmpeg; gmg::Error with its message when it failed.
  void finish();

 private:
  [[noreturn]] void fail(const std::string& what);
  void stop();
  std::string log_tail() const;
  std::string read_log() const;

  EncoderSettings settings_;
  pid_t pid_ = -1;
  int pipe_fd_ = -1;
  int temp_slot_ = -1;  // settings_.output in the interrupt registry (engine/core/interrupt.h)
  // ffmpeg's messages (its stderr): a temporary file unlinked as soon as it is opened, so that
  // nothing is left in the temporary directory even when gmg is killed; read through this fd.
  int log_fd_ = -1;
};

}  // namespace gmg::render
