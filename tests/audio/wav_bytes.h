// Hand-made WAV bytes for the WAV reader's tests (tests/audio/test_wav*.cpp): little-endian
// fields, chunks, a fmt chunk of any format, and reading them back with the errors expected.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "audio/wav.h"
#include "engine/core/error.h"
#include "tests/test_support.h"

namespace gmg::testing::wav {

using gmg::audio::Audio;

inline void le16(std::string& s, std::uint32_t v) {
  s.push_back(static_cast<char>(v & 0xFF));
  s.push_back(static_cast<char>((v >> 8) & 0xFF));
}
inline void le24(std::string& s, std::uint32_t v) {
  le16(s, v & 0xFFFF);
  s.push_back(static_cast<char>((v >> 16) & 0xFF));
}
inline void le32(std::string& s, std::uint32_t v) {
  le16(s, v & 0xFFFF);
  le16(s, v >> 16);
}
inline void le64(std::string& s, std::uint64_t v) {
  le32(s, static_cast<std::uint32_t>(v & 0xFFFFFFFFu));
  le32(s, static_cast<std::uint32_t>(v >> 32));
}
inline void f32(std::string& s, float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  le32(s, u);
}
inline void f64(std::string& s, double d) {
  std::uint64_t u;
  std::memcpy(&u, &d, 8);
  le64(s, u);
}

struct Fmt {
  std::uint16_t tag = 1;  // 1 PCM, 3 float, 0xFFFE extensible
  std::uint16_t channels = 1;
  std::uint32_t rate = 16000;
  std::uint16_t bits = 16;
  std::uint16_t subformat = 1;  // for extensible
};

inline std::string chunk(const std::string& id, const std::string& body, bool pad = true) {
  std::string s = id;
  le32(s, static_cast<std::uint32_t>(body.size()));
  s += body;
  if (pad && (body.size() & 1)) s.push_back('\0');
  return s;
}

inline std::string fmt_chunk(const Fmt& f) {
  std::string b;
  le16(b, f.tag);
  le16(b, f.channels);
  le32(b, f.rate);
  const std::uint32_t align = f.channels * (f.bits / 8u);
  le32(b, f.rate * align);
  le16(b, align);
  le16(b, f.bits);
  if (f.tag == 0xFFFE) {
    le16(b, 22);      // cbSize
    le16(b, f.bits);  // valid bits
    le32(b, 0);       // channel mask
    le16(b, f.subformat);
    const unsigned char tail[14] = {0x00, 0x00, 0x00, 0x00, 0x10, 0x00, 0x80, 0x00, 0x00, 0xAA, 0x00, 0x38, 0x9B, 0x71};
    b.append(reinterpret_cast<const char*>(tail), 14);
  }
  return chunk("fmt ", b);
}

// RIFF/WAVE around the given chunks.
inline std::string riff(const std::string& chunks) {
  std::string s = "RIFF";
  le32(s, static_cast<std::uint32_t>(4 + chunks.size()));
  return s + "WAVE" + chunks;
}

inline std::string wav(const Fmt& f, const std::string& data) { return riff(fmt_chunk(f) + chunk("data", data)); }

// Writes `bytes` to a file in `dir` and reads it back.
inline Audio read_bytes(const TempDir& dir, const std::string& name, const std::string& bytes) {
  const std::string path = dir.file(name);
  write_text(path, bytes);
  return gmg::audio::read_wav(path);
}

// Expects read_wav to throw a gmg::Error whose message names the file and
// contains every one of `parts`.
inline void expect_wav_error(const TempDir& dir, const std::string& name, const std::string& bytes,
                             const std::vector<std::string>& parts) {
  const std::string path = dir.file(name);
  write_text(path, bytes);
  try {
    gmg::audio::read_wav(path);
    ADD_FAILURE() << name << ": expected an error";
  } catch (const gmg::Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(name), std::string::npos) << msg;
    for (const std::string& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "missing '" << p << "' in: " << msg;
  }
}

}  // namespace gmg::testing::wav
