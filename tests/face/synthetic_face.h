// A synthetic reference for the face track's tests: a speaker whose jaw opens exactly on loud open
// vowels (AA, AE, AH) and closes on m, b and p, with the speech's face features saying so (loud on
// vowels, quiet on bilabials, silent between words), and new speech built from phones the same way.
#pragma once

#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "audio/face_features.h"
#include "graph/motion_graph.h"
#include "text/phones.h"

namespace gmg::testing {

inline constexpr double kFps = 30.0;
inline constexpr double kOpen = 0.4;     // the jaw's angle on an open vowel, radians
inline constexpr double kMiddle = 0.15;  // on any other phone
inline constexpr double kClosed = 0.0;   // on m, b, p and in silence

inline double jaw_of(const std::string& symbol) {
  const text::Viseme v = text::viseme_of(symbol);
  if (v == text::Viseme::OpenVowel) return kOpen;
  if (v == text::Viseme::Bilabial || v == text::Viseme::Silence) return kClosed;
  return kMiddle;
}

// Loudness of a phone's frames (audio/face_features.h's first feature).
inline float loudness_of(const std::string& symbol) {
  const text::Viseme v = text::viseme_of(symbol);
  if (v == text::Viseme::Silence) return -4.0f;
  if (v == text::Viseme::OpenVowel) return 0.5f;
  if (v == text::Viseme::Bilabial) return -1.5f;
  return -0.5f;
}

// Phones spoken one after another from `start` s, each `frames[i % frames.size()]` frames long,
// the words separated by a silence of 6 frames (a "" in `symbols`).
inline std::vector<text::Phone> phones_of(const std::vector<std::string>& symbols, const std::vector<int>& frames) {
  std::vector<text::Phone> out;
  double t = 0.2;
  for (std::size_t i = 0; i < symbols.size(); ++i) {
    if (symbols[i].empty()) {
      t += 6.0 / kFps;
      continue;
    }
    const double length = frames[i % frames.size()] / kFps;
    out.push_back({t, t + length, symbols[i]});
    t += length;
  }
  return out;
}

inline std::string symbol_at(const std::vector<text::Phone>& phones, int frame) {
  const double t = frame / kFps;
  for (const text::Phone& p : phones)
    if (t >= p.start && t < p.end) return p.symbol;
  return "";
}

// Face features of speech with these phones: loudness by phone, a band that marks bilabials.
inline std::vector<float> features_of(const std::vector<text::Phone>& phones, int frames) {
  constexpr int D = audio::FaceFeatures::kDims;
  std::vector<float> z(static_cast<std::size_t>(frames) * D, 0.0f);
  for (int f = 0; f < frames; ++f) {
    const std::string s = symbol_at(phones, f);
    z[static_cast<std::size_t>(f) * D] = loudness_of(s);
    z[static_cast<std::size_t>(f) * D + 2] = text::viseme_of(s) == text::Viseme::Bilabial ? 1.0f : 0.0f;
  }
  return z;
}

// A graph of one clip of `frames` frames spoken with `phones`: a root and a jaw (turning about X by
// the phone's jaw angle), three expression coefficients (the jaw angle, its negative times 2, and a
// slow wave) and the face speech as gmg build keeps it.
inline MotionGraph face_graph(const std::vector<text::Phone>& phones, int frames, bool with_phones = true) {
  MotionGraph g;
  Skeleton sk;
  Joint root;
  root.name = "pelvis";
  root.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition,
                   Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  Joint jaw;
  jaw.name = "jaw";
  jaw.parent = 0;
  jaw.offset = glm::dvec3(0, 1, 0);
  jaw.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
  sk.joints = {root, jaw};
  g.motion = motion_rest(sk, kFps, frames);
  g.clips = {{"face.bvh", 0, frames}};
  g.body.expression_dims = 3;
  FaceSpeech& fs = g.face_speech;
  fs.feature_dims = audio::FaceFeatures::kDims;
  fs.features = features_of(phones, frames);
  for (int f = 0; f < frames; ++f) {
    const double a = jaw_of(symbol_at(phones, f));
    g.motion.rotations[g.motion.index(f, 1)] = glm::angleAxis(a, glm::dvec3(1, 0, 0));
    g.body.expressions.insert(g.body.expressions.end(), {a, -2.0 * a, 0.3 * std::sin(f * 0.05)});
    fs.jaw.vec().push_back(static_cast<float>(a));
  }
  if (with_phones) {
    for (const text::Phone& p : phones) {
      auto it = std::find(fs.symbols.begin(), fs.symbols.end(), p.symbol);
      if (it == fs.symbols.end()) it = fs.symbols.insert(fs.symbols.end(), p.symbol);
      fs.phones.push_back({p.start * kFps, p.end * kFps, static_cast<std::uint32_t>(it - fs.symbols.begin())});
    }
  }
  return g;
}

}  // namespace gmg::testing
