// gmg_fuzz_seeds DIR: writes the seed corpus of every harness in tests/fuzz into DIR/<harness>/.
//
// The seeds are made by the project itself, so they follow the readers: valid files written by
// gmg's own writers (a short synthetic speaker's BVH, WAV and TSV, the default config, a small
// hand-made graph), the other variants the readers accept (TextGrid long and short, UTF-16,
// Google JSON times in all three forms, float and 24-bit WAV, quoted CSV), and a few hostile
// ones from the issue (a lying Frames: header, a 1 Hz WAV, a deep hierarchy, 1e309).
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "audio/wav.h"
#include "engine/config/config.h"
#include "engine/core/files.h"
#include "engine/motion/bvh.h"
#include "engine/motion/npz.h"
#include "engine/synth/synth.h"
#include "graph/graph_builder.h"
#include "graph/graph_io.h"
#include "graph/reference_facts.h"
#include "tests/fuzz/fuzz_common.h"

namespace fs = std::filesystem;

namespace {

void put(const fs::path& dir, const std::string& name, const std::string& bytes) {
  fs::create_directories(dir);
  std::ofstream out(dir / name, std::ios::binary);
  out << bytes;
}

template <typename T>
void append(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

// A RIFF/WAVE file with a 16-byte fmt chunk (format tag, channels, rate, bits) and `data`.
std::string wav_bytes(std::uint16_t tag, std::uint16_t channels, std::uint32_t rate, std::uint16_t bits,
                      const std::string& data) {
  std::string fmt;
  append<std::uint16_t>(fmt, tag);
  append<std::uint16_t>(fmt, channels);
  append<std::uint32_t>(fmt, rate);
  append<std::uint32_t>(fmt, rate * channels * bits / 8);
  append<std::uint16_t>(fmt, static_cast<std::uint16_t>(channels * bits / 8));
  append<std::uint16_t>(fmt, bits);
  std::string out = "RIFF";
  append<std::uint32_t>(out, static_cast<std::uint32_t>(4 + 8 + fmt.size() + 8 + data.size()));
  out += "WAVEfmt ";
  append<std::uint32_t>(out, static_cast<std::uint32_t>(fmt.size()));
  out += fmt + "data";
  append<std::uint32_t>(out, static_cast<std::uint32_t>(data.size()));
  return out + data;
}

void bvh_seeds(const fs::path& dir, const gmg::SynthClip& clip) {
  put(dir, "synth.bvh", gmg::bvh_format(gmg::motion_slice(clip.motion, 0, 3)));
  const std::string chain =
      "HIERARCHY\r\nROOT root\r\n{\r\n\tOFFSET 0 0 0\r\n\tCHANNELS 6 Xposition Yposition Zposition Zrotation "
      "Xrotation Yrotation\r\n\tJOINT mid\r\n\t{\r\n\t\tOFFSET 0 1 0\r\n\t\tCHANNELS 3 Yrotation Zrotation "
      "Xrotation\r\n\t\tEnd Site\r\n\t\t{\r\n\t\t\tOFFSET 0 1 0\r\n\t\t}\r\n\t}\r\n}\r\nMOTION\r\nFrames: 2\r\n"
      "Frame Time: 0.0333333\r\n0 0 0 0 0 0 10 20 30\r\n1 2 3 40 50 60 70 80 90\r\n";
  put(dir, "chain.bvh", chain);
  std::string lying = chain;
  lying.replace(lying.find("Frames: 2"), 9, "Frames: 10000000");
  put(dir, "lying_frames.bvh", lying);
  std::string deep = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
  for (int i = 0; i < 40; ++i) deep += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\n";
  for (int i = 0; i <= 40; ++i) deep += "}\n";
  put(dir, "deep.bvh", deep + "MOTION\nFrames: 1\nFrame Time: 0.01\n5\n");
  // Binary bytes where a token should be: the message quotes them escaped.
  put(dir, "binary.bvh", std::string("HIERARCHY\nROOT \x1b[31m\x07\xff\xfe\n{\nOFFSET 0 0 0\n"));
}

void wav_seeds(const fs::path& dir, const gmg::SynthClip& clip) {
  gmg::audio::Audio a = clip.audio;
  a.samples.resize(std::min<std::size_t>(a.samples.size(), 800));
  const fs::path tmp = dir / "pcm16.wav";
  fs::create_directories(dir);
  gmg::audio::write_wav_pcm16(tmp.string(), a);
  std::string pcm24, f32;
  for (int i = 0; i < 200; ++i) {
    const float v = static_cast<float>(i % 20) / 20.0f - 0.5f;
    const std::int32_t s = static_cast<std::int32_t>(v * 8388607);
    pcm24.append(
        {static_cast<char>(s & 0xFF), static_cast<char>((s >> 8) & 0xFF), static_cast<char>((s >> 16) & 0xFF)});
    append<float>(f32, v);
  }
  put(dir, "pcm24_stereo.wav", wav_bytes(1, 2, 48000, 24, pcm24));
  put(dir, "float32.wav", wav_bytes(3, 1, 44100, 32, f32));
  put(dir, "pcm8.wav", wav_bytes(1, 1, 8000, 8, std::string(100, '\x80')));
  put(dir, "one_hz.wav", wav_bytes(1, 1, 1, 16, std::string(200, '\x01')));
  put(dir, "ten_mhz.wav", wav_bytes(1, 1, 10000019, 16, std::string(16, '\x01')));
}

// What is given as speech but cannot be: silence, 10 ms, quiet hiss, and files that are not WAV.
void audio_bytes_seeds(const fs::path& dir) {
  put(dir, "silence.wav", wav_bytes(1, 1, 8000, 16, std::string(16000, '\0')));
  put(dir, "ten_ms.wav", wav_bytes(1, 1, 8000, 16, std::string(160, '\x40')));
  std::string hiss;
  for (int i = 0; i < 8000; ++i) append<std::int16_t>(hiss, static_cast<std::int16_t>((i * 7919) % 17 - 8));
  put(dir, "hiss.wav", wav_bytes(1, 1, 8000, 16, hiss));
  put(dir, "text.wav", "0.5\t0.9\thello\n");
  put(dir, "id3.wav", std::string("ID3\x04\0\0\0\0\0\x10\xff\xfb\x90\x64", 14));
  put(dir, "hierarchy.wav", "HIERARCHY\nROOT hips\n");
  put(dir, "escape.bin", std::string("\x1b]0;title\x07\xc2\x9b\xe2\x80\xae\xf4\x90\x80\x80\xed\xa0\x80"));
}

void transcript_seeds(const fs::path& root, const gmg::SynthClip& clip) {
  std::string tsv;
  for (std::size_t i = 0; i < clip.words.size() && i < 8; ++i)
    tsv += std::to_string(clip.words[i].start) + "\t" + std::to_string(clip.words[i].end) + "\t" + clip.words[i].text +
           "\n";
  put(root / "tsv", "synth.tsv", tsv);
  put(root / "tsv", "spaces_crlf.tsv", "0.5  0.9  hello there\r\n1.0 1.2 #\r\n\r\n");
  put(root / "tsv", "binary.tsv", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR\t\x1b[2J\n", 22));
  const std::string long_grid =
      "File type = \"ooTextFile\"\nObject class = \"TextGrid\"\n\nxmin = 0 \nxmax = 2 \ntiers? <exists> \nsize = 1 \n"
      "item []: \n    item [1]:\n        class = \"IntervalTier\" \n        name = \"words\" \n        xmin = 0 \n"
      "        xmax = 2 \n        intervals: size = 2 \n        intervals [1]:\n            xmin = 0 \n"
      "            xmax = 1 \n            text = \"\" \n        intervals [2]:\n            xmin = 1 \n"
      "            xmax = 2 \n            text = \"say \"\"this\"\"\" \n";
  put(root / "textgrid", "long.TextGrid", long_grid);
  put(root / "textgrid", "short.TextGrid",
      "File type = \"ooTextFile\"\nObject class = \"TextGrid\"\n0\n2\n<exists>\n1\n\"IntervalTier\"\n\"words\"\n0\n2\n"
      "2\n0\n1\n\"\"\n1\n2\n\"word\"\n");
  std::string utf16 = "\xFF\xFE";
  for (char c : long_grid) utf16 += std::string{c, '\0'};
  put(root / "textgrid", "utf16.TextGrid", utf16);
  put(root / "google_json", "times.json",
      R"({"results": [{"alternatives": [{"words": [)"
      R"({"start_time": "0.5s", "end_time": "0.9s", "word": "hello"},)"
      R"({"startTime": 1.0, "endTime": {"seconds": "1", "nanos": 500000000}, "word": "there"}]}]}]})");
  put(root / "google_json", "array.json", R"([{"alternatives": [{"words": []}]}, {"alternatives": []}])");
  put(root / "google_json", "huge_number.json",
      R"([{"alternatives": [{"words": [{"start_time": 1e309, "end_time": 2, "word": "x"}]}]}])");
}

// A hand-made graph: 2 joints, 10 frames in two clips, an onset, a keyword and a break node, one
// transition. Small, so mutations reach every field quickly.
gmg::MotionGraph tiny_graph() {
  const gmg::Skeleton sk = gmg::fuzz::two_joint_skeleton();
  gmg::MotionGraph g;
  g.motion = gmg::motion_rest(sk, 30.0, 10);
  g.clips = {{"a.bvh", 0, 6}, {"b.bvh", 6, 4}};
  gmg::GraphBuilder b(10);
  for (int f = 0; f + 1 < 10; ++f)
    if (f != 5) b.add_edge(f, f + 1, gmg::EdgeInfo{0.0});
  b.add_edge(2, 8, gmg::EdgeInfo{0.25});
  b.node(1).kinds = gmg::kOnsetNode;
  b.node(3).kinds = gmg::kKeywordNode;
  b.node(3).keyword = "big";
  b.node(5).kinds = gmg::kBreakNode;
  b.node(9).kinds = gmg::kBreakNode;
  b.finish(g);
  gmg::add_reference_facts(g);  // so the seed reaches the reference facts' checks
  return g;
}

void graph_seeds(const fs::path& dir) {
  fs::create_directories(dir);
  const fs::path path = dir / "tiny.gmg";
  gmg::graph_save(path.string(), tiny_graph());
  const std::string file = gmg::read_file_bytes(path.string());
  fs::remove(path);
  // The harness's first byte: 0 = a whole file, 1 = the checksum's extent (u64, the header's last
  // field) and a payload it wraps with a valid checksum.
  put(dir, "whole.seed", std::string(1, '\0') + file);
  const std::size_t header = 8 + 4 + 8 + 8;
  put(dir, "payload.seed",
      std::string(1, '\1') + file.substr(header - 8, 8) + file.substr(header, file.size() - header - 8));
}

void config_seeds(const fs::path& dir) {
  put(dir, "defaults.json", gmg::config_to_json(gmg::Config{}));
  put(dir, "some.json",
      R"({"l_pn": 2, "w_full": [1, 0.5, 0.5, 0.2, 0.2, 0.2, 0.1, 0.1, 0.1, 0.1], )"
      R"("lock_joints": ["a", "b"], "init": "random", "seed": 18446744073709551615})");
  put(dir, "huge.json", R"({"l_npaths": 1e309})");
  // A misspelt key and a misspelt mode: errors that suggest the nearest name.
  put(dir, "typos.json", R"({"l_pm": 3, "planner": "papr"})");
}

void csv_seeds(const fs::path& dir) {
  put(dir, "manifest.csv",
      "stem,bvh,wav,transcript\n# a comment\na,a.bvh,a.wav,none\n\"b, c\",\"x\"\"y\".bvh,b.wav,\n");
  put(dir, "pairs.csv", "\xEF\xBB\xBFtest_stem,reference_stem\r\nt1,r1\r\n");
}

}  // namespace

// Archives gmg writes for the two-joint skeleton (whole and fractional frame rate; with a body:
// betas, a face, gender and model), and one whose `poses` is cut short.
void npz_seeds(const fs::path& dir) {
  gmg::Motion m = gmg::motion_rest(gmg::fuzz::two_joint_skeleton(), 30.0, 4);
  m.rotations[m.index(2, 1)] = glm::angleAxis(0.5, glm::dvec3(0, 0, 1));
  const std::string whole = gmg::npz_format(m, "seed.npz");
  put(dir, "rest.npz", whole);
  m.fps = 29.97;
  put(dir, "ntsc.npz", gmg::npz_format(m, "seed.npz"));
  put(dir, "cut.npz", whole.substr(0, whole.size() / 2));
  gmg::SmplxBody body;
  body.betas = {0.5, -1.0};
  body.expression_dims = 2;
  body.expressions = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8};
  body.gender = "female";
  put(dir, "body.npz", gmg::npz_format(m, "seed.npz", body));
}

// Whisper (segments[].words[]) and WhisperX (with word_segments[] and an untimed word).
void whisper_seeds(const fs::path& dir) {
  put(dir, "whisper.json",
      R"({"text": " Hello there.", "segments": [{"start": 0.0, "end": 1.2, "text": " Hello there.",)"
      R"( "words": [{"word": " Hello", "start": 0.1, "end": 0.5}, {"word": " there.", "start": 0.6, "end": 1.1}]}]})");
  put(dir, "whisperx.json",
      R"({"segments": [{"start": 0.0, "end": 2.0, "words": [{"word": "It", "start": 0.1, "end": 0.3},)"
      R"( {"word": "1984"}, {"word": "ended", "start": 1.2, "end": 1.6}]}],)"
      R"( "word_segments": [{"word": "It", "start": 0.1, "end": 0.3}]})");
  put(dir, "no_words.json", R"({"segments": [{"start": 0, "end": 1, "text": "hi"}]})");
  put(dir, "google.json", R"([{"alternatives": [{"words": [{"startTime": "0s", "endTime": "1s", "word": "x"}]}]}])");
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: gmg_fuzz_seeds DIR\n";
    return 2;
  }
  try {
    const fs::path root(argv[1]);
    gmg::SynthSpec spec;
    spec.duration_s = 3.0;
    spec.sample_rate = 8000;
    const gmg::SynthClip clip = gmg::synth_speaker(spec);
    bvh_seeds(root / "bvh", clip);
    wav_seeds(root / "wav", clip);
    transcript_seeds(root, clip);
    graph_seeds(root / "graph");
    config_seeds(root / "config");
    csv_seeds(root / "csv");
    npz_seeds(root / "npz");
    whisper_seeds(root / "whisper_json");
    audio_bytes_seeds(root / "audio_bytes");
  } catch (const std::exception& e) {
    std::cerr << "gmg_fuzz_seeds: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
