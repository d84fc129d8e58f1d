#include "engine/render/encoder.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/interrupt.h"
#include "engine/core/strings.h"

extern char** environ;

namespace gmg::render {
namespace {

bool is_executable_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

const char* native_pixel_format() {
  // Cairo keeps a pixel as one native 32-bit word 0xXXRRGGBB.
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  return "0rgb";
#else
  return "bgr0";
#endif
}

std::vector<std::string> ffmpeg_arguments(const EncoderSettings& s) {
  const Rational rate = fps_rational(s.fps);
  std::vector<std::string> a = {s.ffmpeg,      "-hide_banner",
                                "-nostdin",    "-loglevel",
                                "error",       "-y",
                                "-f",          "rawvideo",
                                "-pix_fmt",    native_pixel_format(),
                                "-video_size", std::to_string(s.width) + "x" + std::to_string(s.height),
                                "-framerate",  std::to_string(rate.num) + "/" + std::to_string(rate.den),
                                "-i",          "pipe:0"};
  if (!s.audio.empty()) {
    // Input options: the audio is cut, sample-accurately, to the video's range.
    if (s.audio_from_s > 0) a.insert(a.end(), {"-ss", format_number(s.audio_from_s)});
    if (s.audio_for_s >= 0) a.insert(a.end(), {"-t", format_number(s.audio_for_s)});
    a.insert(a.end(), {"-i", s.audio});
  }
  a.insert(a.end(), {"-map", "0:v:0"});
  if (!s.audio.empty()) a.insert(a.end(), {"-map", "1:a:0"});
  // passthrough: one output frame per input frame, whatever the muxer's defaults; no -shortest,
  // so neither stream is cut to the other's length.
  a.insert(a.end(), {"-c:v", "libx264", "-preset", s.preset, "-crf", std::to_string(s.crf), "-pix_fmt", "yuv420p",
                     "-fps_mode", "passthrough"});
  // 48 kHz: an AAC frame (1024 samples) is then shorter than a video frame, so the audio's padded
  // end stays within a frame of the WAV's length.
  if (!s.audio.empty()) a.insert(a.end(), {"-c:a", "aac", "-b:a", "160k", "-ar", "48000"});
  // The container comes from the user's name: the temporary's own name ends in ".tmp<pid>_<n>".
  const std::string& name = s.name.empty() ? s.output : s.name;
  if (ends_with_ci(name, ".mp4") || ends_with_ci(name, ".mov")) a.insert(a.end(), {"-movflags", "+faststart"});
  a.insert(a.end(), {"-f", ends_with_ci(name, ".mkv") ? "matroska" : ends_with_ci(name, ".mov") ? "mov" : "mp4"});
  a.push_back(s.output);
  return a;
}

// The cause of a failed encode when ffmpeg's messages name one the user can act on: the disk or
// the folder, not the codec. "" when none does.
std::string write_failure(const std::string& log) {
  for (const int err : {ENOSPC, EDQUOT, EROFS, EACCES, EIO, EFBIG}) {
    std::string text = std::strerror(err);
    if (log.find(text) != std::string::npos) return text;
  }
  return "";
}

bool write_all(int fd, const unsigned char* p, std::size_t n) {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t k = ::write(fd, p + done, n - done);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    done += static_cast<std::size_t>(k);
  }
  return true;
}

}  // namespace

std::string find_executable(const std::string& name) {
  if (name.empty()) return "";
  if (name.find('/') != std::string::npos) return is_executable_file(name) ? name : "";
  const char* path = std::getenv("PATH");
  if (path == nullptr) return "";
  for (const std::string& dir : split_trimmed(path, ':')) {
    std::string candidate = dir;
    candidate += '/';
    candidate += name;
    if (is_executable_file(candidate)) return candidate;
  }
  return "";
}

Rational fps_rational(double fps) {
  if (std::abs(fps - std::round(fps)) < 1e-4 * fps) return {std::lround(fps), 1};
  const double ntsc = fps * 1001.0 / 1000.0;
  if (std::abs(ntsc - std::round(ntsc)) < 1e-4 * fps) return {std::lround(ntsc) * 1000, 1001};
  return {std::lround(fps * 1000.0), 1000};
}

VideoEncoder::VideoEncoder(const EncoderSettings& settings) : settings_(settings) {
  std::string log_template = (std::filesystem::temp_directory_path() / "gmg_ffmpeg_XXXXXX").string();
  const int log_fd = ::mkostemp(log_template.data(), O_CLOEXEC);
  if (log_fd < 0) throw Error(settings_.name + ": cannot create a temporary file for ffmpeg's messages");
  ::unlink(log_template.c_str());  // the open descriptors keep it: ffmpeg writes, log_tail() reads
  log_fd_ = log_fd;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    ::close(log_fd);
    log_fd_ = -1;
    throw Error(settings_.name + ": cannot open a pipe to ffmpeg (" + std::strerror(errno) + ")");
  }
  const std::vector<std::string> args = ffmpeg_arguments(settings_);
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  // Registered before ffmpeg creates it, so a second Ctrl-C (which ends gmg at once) removes it.
  temp_slot_ = register_temporary_file(settings_.output);
  const pid_t parent = ::getpid();
  // fork and exec rather than posix_spawn: the child asks the kernel to kill it when gmg dies
  // (PR_SET_PDEATHSIG), so no ffmpeg outlives a gmg that was killed, even by SIGKILL. Between
  // the two only async-signal-safe calls.
  pid_ = ::fork();
  if (pid_ == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // gmg died before the request took hold
    ::dup2(fds[0], 0);
    ::dup2(null_fd, 1);
    ::dup2(log_fd, 2);
    ::execve(argv[0], argv.data(), environ);
    ::_exit(127);
  }
  const int fork_error = errno;
  ::close(fds[0]);
  if (null_fd >= 0) ::close(null_fd);
  pipe_fd_ = fds[1];
  if (pid_ < 0) {
    pid_ = -1;
    stop();
    throw Error(settings_.ffmpeg + ": cannot run (" + std::strerror(fork_error) + ")");
  }
}

VideoEncoder::~VideoEncoder() { stop(); }

void VideoEncoder::stop() {
  if (pipe_fd_ >= 0) ::close(pipe_fd_);
  pipe_fd_ = -1;
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    std::error_code ec;
    std::filesystem::remove(settings_.output, ec);
  }
  unregister_temporary_file(temp_slot_);
  temp_slot_ = -1;
  if (log_fd_ >= 0) ::close(log_fd_);
  log_fd_ = -1;
}

std::string VideoEncoder::read_log() const {
  std::string log;
  if (log_fd_ < 0) return log;
  char buffer[4096];
  for (;;) {
    const ssize_t got = ::pread(log_fd_, buffer, sizeof buffer, static_cast<off_t>(log.size()));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    log.append(buffer, static_cast<std::size_t>(got));
  }
  return log;
}

std::string VideoEncoder::log_tail() const {
  const std::string log = read_log();
  std::vector<std::string> lines = split_lines(log);
  std::string out;
  const std::size_t from = lines.size() > 4 ? lines.size() - 4 : 0;
  for (std::size_t i = from; i < lines.size(); ++i)
    if (!trim(lines[i]).empty()) out += (out.empty() ? "" : "; ") + std::string(trim(lines[i]));
  return out.empty() ? "no message" : out;
}

void VideoEncoder::fail(const std::string& what) {
  std::string log = log_tail();
  // ffmpeg names the temporary it writes; the user knows the output's name.
  for (std::size_t at = log.find(settings_.output); !settings_.name.empty() && at != std::string::npos;
       at = log.find(settings_.output, at + settings_.name.size()))
    log.replace(at, settings_.output.size(), settings_.name);
  const std::string cause = write_failure(log);
  const std::string message = settings_.name + ": " +
                              (cause.empty() ? what : "cannot write the video (" + cause + ")") +
                              " (ffmpeg: " + escape_nonprintable(log) + ")";
  stop();
  throw Error(message);
}

void VideoEncoder::write_frame(const unsigned char* pixels, int stride) {
  const std::size_t row = static_cast<std::size_t>(settings_.width) * 4;
  // A dead ffmpeg must show up as EPIPE here, not kill gmg with SIGPIPE.
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &previous);
  bool ok = true;
  if (static_cast<std::size_t>(stride) == row) {
    ok = write_all(pipe_fd_, pixels, row * static_cast<std::size_t>(settings_.height));
  } else {
    for (int y = 0; y < settings_.height && ok; ++y)
      ok = write_all(pipe_fd_, pixels + static_cast<std::size_t>(y) * static_cast<std::size_t>(stride), row);
  }
  ::sigaction(SIGPIPE, &previous, nullptr);
  if (!ok) fail("ffmpeg stopped while encoding");
}

void VideoEncoder::finish() {
  ::close(pipe_fd_);
  pipe_fd_ = -1;
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  // ffmpeg may end with 0 after failed writes (a full disk while it writes the trailer), so its
  // messages decide too: a video it could not write whole is no video.
  const std::string log = read_log();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !write_failure(log).empty()) {
    std::error_code ec;
    std::filesystem::remove(settings_.output, ec);
    fail("ffmpeg could not encode the video");
  }
  stop();
}

}  // namespace gmg::render
