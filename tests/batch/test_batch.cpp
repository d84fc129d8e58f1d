// gmg batch: pairing, parallel reenactment, broken inputs, resumption, manifests, the CLI (the
// draw of references and a pool of the shared recordings: test_batch_pool.cpp).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "audio/wav.h"
#include "engine/batch/batch.h"
#include "engine/cli/cli_common.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/motion/bvh.h"
#include "engine/synth/synth.h"
#include "tests/test_support.h"

namespace gmg {

// Status names in failure messages.
std::ostream& operator<<(std::ostream& os, BatchClipStatus s) { return os << enum_name(kBatchClipStatusNames, s); }

namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::write_text;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string slurp(const fs::path& p) { return read_file_bytes(p.string()); }

// Synthetic data, made once for the whole suite:
//   pool/{bvh,wav,tsv}/ref_a, ref_b, ref_c (GENEA layout, 20 s each, different speakers) and
//   ref_broken (a BVH cut in half, a good WAV);
//   tests_flat/tst_01..tst_05 (.wav, .tsv and a ground-truth .bvh that batch must ignore) and
//   tst_bad.wav (empty file); tests_genea/{wav,tsv}/ the same clips in GENEA layout.
class BatchData : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    const fs::path root = dir_->path();
    const fs::path scratch = root / "scratch";
    const char* refs[] = {"ref_a", "ref_b", "ref_c"};
    for (int i = 0; i < 3; ++i) {
      SynthSpec s;
      s.duration_s = 20.0;
      s.seed = 100 + static_cast<std::uint64_t>(i);
      s.style = 0.3 * i;
      synth_write(synth_speaker(s), scratch.string(), refs[i]);
      for (const char* ext : {"bvh", "wav", "tsv"}) {
        fs::create_directories(root / "pool" / ext);
        const std::string name = std::string(refs[i]) + "." + ext;
        fs::copy_file(scratch / name, root / "pool" / ext / name);
      }
    }
    const std::string bvh = slurp(root / "pool" / "bvh" / "ref_a.bvh");
    write_text((root / "pool" / "bvh" / "ref_broken.bvh").string(), bvh.substr(0, bvh.size() / 2));
    fs::copy_file(root / "pool" / "wav" / "ref_a.wav", root / "pool" / "wav" / "ref_broken.wav");

    fs::create_directories(root / "tests_flat");
    fs::create_directories(root / "tests_genea" / "wav");
    fs::create_directories(root / "tests_genea" / "tsv");
    for (int i = 1; i <= 5; ++i) {
      const std::string stem = "tst_0" + std::to_string(i);
      SynthSpec s;
      s.duration_s = 6.0 + 0.5 * i;
      s.seed = 200 + static_cast<std::uint64_t>(i);
      s.style = 0.2 * (i - 1);
      synth_write(synth_speaker(s), (root / "tests_flat").string(), stem);
      fs::copy_file(root / "tests_flat" / (stem + ".wav"), root / "tests_genea" / "wav" / (stem + ".wav"));
      fs::copy_file(root / "tests_flat" / (stem + ".tsv"), root / "tests_genea" / "tsv" / (stem + ".tsv"));
    }
    write_text((root / "tests_flat" / "tst_bad.wav").string(), "");
    write_text((root / "tests_genea" / "wav" / "tst_bad.wav").string(), "");
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static fs::path root() { return dir_->path(); }
  static std::string pool() { return (root() / "pool").string(); }
  static std::string tests_flat() { return (root() / "tests_flat").string(); }
  static std::string tests_genea() { return (root() / "tests_genea").string(); }

  static const std::vector<std::string>& test_stems() {
    static const std::vector<std::string> s = {"tst_01", "tst_02", "tst_03", "tst_04", "tst_05", "tst_bad"};
    return s;
  }
  static const std::vector<std::string>& pool_stems() {
    static const std::vector<std::string> s = {"ref_a", "ref_b", "ref_broken", "ref_c"};
    return s;
  }

  // A seed whose draw pairs some good test clip with ref_broken, some with a good reference, and
  // the broken test clip with a good reference (so its own error shows).
  static std::uint64_t seed_with_broken_draw() {
    for (std::uint64_t seed = 1;; ++seed) {
      const auto d = batch_draw_references(test_stems(), pool_stems(), seed);
      int broken = 0, good = 0;
      for (std::size_t i = 0; i + 1 < d.size(); ++i) (d[i] == "ref_broken" ? broken : good) += 1;
      if (broken >= 1 && good >= 3 && d.back() != "ref_broken") return seed;
    }
  }

  static BatchOptions options(const std::string& out) {
    BatchOptions o;
    o.pool_dirs = {pool()};
    o.test_dirs = {tests_flat()};
    o.output_dir = out;
    o.jobs = 2;
    o.progress = BatchProgress::Lines;
    return o;
  }

  static std::map<std::string, const BatchClipResult*> by_stem(const BatchSummary& s) {
    std::map<std::string, const BatchClipResult*> m;
    for (const BatchClipResult& c : s.clips) m[c.test_stem] = &c;
    return m;
  }

  static int expected_frames(const std::string& wav, double fps) {
    return static_cast<int>(std::lround(audio::read_wav(wav).duration() * fps));
  }

  static bool has_temporaries(const fs::path& dir) {
    for (const auto& e : fs::directory_iterator(dir))
      if (contains(e.path().filename().string(), ".tmp")) return true;
    return false;
  }

  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> BatchData::dir_;

TEST_F(BatchData, CompletesGoodClipsReportsBrokenOnesAndIsReproducible) {
  TempDir out1, out2;
  const std::uint64_t seed = seed_with_broken_draw();
  const auto draw = batch_draw_references(test_stems(), pool_stems(), seed);

  BatchOptions o = options(out1.path().string());
  o.seed = seed;
  std::ostringstream log;
  const BatchSummary s = batch_run(o, Config{}, log);
  ASSERT_EQ(s.clips.size(), 6u);
  EXPECT_EQ(s.seed, seed);
  EXPECT_EQ(s.jobs, 2);
  EXPECT_EQ(s.references.size(), 4u);

  int expect_failed = 0;
  for (std::size_t i = 0; i < s.clips.size(); ++i) {
    const BatchClipResult& c = s.clips[i];
    EXPECT_EQ(c.test_stem, test_stems()[i]);
    EXPECT_EQ(c.reference_stem, draw[i]) << c.test_stem;
    if (c.test_stem == "tst_bad") {
      EXPECT_EQ(c.status, BatchClipStatus::Failed);
      EXPECT_TRUE(contains(c.error, "tst_bad.wav")) << c.error;
      EXPECT_FALSE(fs::exists(out1.path() / "tst_bad.bvh"));
      ++expect_failed;
    } else if (c.reference_stem == "ref_broken") {
      EXPECT_EQ(c.status, BatchClipStatus::Failed);
      EXPECT_TRUE(contains(c.error, "ref_broken.bvh")) << c.error;
      EXPECT_FALSE(fs::exists(out1.path() / (c.test_stem + ".bvh")));
      ++expect_failed;
    } else {
      ASSERT_EQ(c.status, BatchClipStatus::Ok) << c.test_stem << ": " << c.error;
      EXPECT_TRUE(c.error.empty());
      EXPECT_EQ(c.output, (out1.path() / (c.test_stem + ".bvh")).string());
      const Motion m = bvh_read(c.output);
      EXPECT_EQ(m.frame_count, expected_frames((root() / "tests_flat" / (c.test_stem + ".wav")).string(), m.fps));
      EXPECT_EQ(c.frames, m.frame_count);
      EXPECT_EQ(m.joint_count(), synth_skeleton().joint_count());
      EXPECT_GT(c.seconds, 0.0);
      EXPECT_EQ(c.failures, 0);
    }
  }
  EXPECT_EQ(s.failed, expect_failed);
  EXPECT_EQ(s.ok, 6 - expect_failed);
  EXPECT_EQ(s.skipped, 0);
  EXPECT_FALSE(s.interrupted);
  for (const BatchReferenceResult& r : s.references) {
    if (r.stem == "ref_broken") {
      EXPECT_TRUE(contains(r.error, "ref_broken.bvh")) << r.error;
    } else if (r.clips > 0) {
      EXPECT_TRUE(r.error.empty()) << r.error;
      EXPECT_EQ(r.frames, 600);
      EXPECT_GT(r.build_seconds, 0.0);
    }
  }

  // Records beside the outputs.
  std::string pairs = "test_stem,reference_stem\n";
  for (std::size_t i = 0; i < draw.size(); ++i) pairs += test_stems()[i] + "," + draw[i] + "\n";
  EXPECT_EQ(slurp(out1.path() / "pairs.csv"), pairs);
  const std::string csv = slurp(out1.path() / "summary.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "test_stem,reference_stem,status,frames,fallbacks,failures,seconds,output,error");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7);
  EXPECT_TRUE(contains(csv, "tst_bad,"));
  const auto j = nlohmann::json::parse(slurp(out1.path() / "summary.json"));
  EXPECT_EQ(j["counts"]["failed"], expect_failed);
  EXPECT_EQ(j["clips"].size(), 6u);
  EXPECT_EQ(j["clips"][5]["test"], "tst_bad");
  EXPECT_EQ(j["clips"][5]["status"], "failed");
  EXPECT_TRUE(j["clips"][5]["error"].is_string());
  EXPECT_EQ(j["seed"], seed);
  EXPECT_FALSE(has_temporaries(out1.path()));
  // Plain progress lines (the stream is not a terminal).
  EXPECT_TRUE(contains(log.str(), "[6/6]")) << log.str();
  EXPECT_TRUE(contains(log.str(), "tst_bad FAILED")) << log.str();
  EXPECT_FALSE(contains(log.str(), "\r"));

  // Same seed, one job, the GENEA layout of the same test clips: identical pairs and bytes.
  BatchOptions o2 = options(out2.path().string());
  o2.test_dirs = {tests_genea()};
  o2.seed = seed;
  o2.jobs = 1;
  std::ostringstream log2;
  const BatchSummary s2 = batch_run(o2, Config{}, log2);
  EXPECT_EQ(s2.failed, s.failed);
  EXPECT_EQ(slurp(out2.path() / "pairs.csv"), pairs);
  for (const BatchClipResult& c : s.clips) {
    if (c.status != BatchClipStatus::Ok) continue;
    EXPECT_EQ(slurp(out1.path() / (c.test_stem + ".bvh")), slurp(out2.path() / (c.test_stem + ".bvh"))) << c.test_stem;
  }
}

TEST_F(BatchData, RerunSkipsFinishedClipsUnlessForcedAndCleansTemporaries) {
  TempDir out;
  BatchOptions o = options(out.path().string());
  o.blacklist = (root() / "blacklist.txt").string();
  const std::string broken = (root() / "pool" / "bvh" / "ref_broken.bvh").string();
  write_text(o.blacklist, "# broken capture\n  " + broken + "  # cut\n\nnot_in_pool\n");
  std::ostringstream log;
  const BatchSummary s1 = batch_run(o, Config{}, log);
  EXPECT_EQ(s1.blacklisted, 1);
  EXPECT_EQ(s1.ok, 5);
  EXPECT_EQ(s1.failed, 1);  // tst_bad only
  for (const BatchClipResult& c : s1.clips) EXPECT_NE(c.reference_stem, "ref_broken");
  const std::string first = slurp(out.path() / "tst_02.bvh");
  const std::string pairs1 = slurp(out.path() / "pairs.csv");
  const auto mtime = fs::last_write_time(out.path() / "tst_02.bvh");

  // A killed run's leftovers: a removed output and a temporary file of a dead process.
  fs::remove(out.path() / "tst_03.bvh");
  write_text((out.path() / "tst_03.bvh.tmp999999999_0").string(), "HIERARCHY\nROOT Hips\n{");
  std::ostringstream log2;
  const BatchSummary s2 = batch_run(o, Config{}, log2);
  const auto m2 = by_stem(s2);
  EXPECT_EQ(s2.skipped, 4);
  EXPECT_EQ(s2.ok, 1);
  EXPECT_EQ(m2.at("tst_03")->status, BatchClipStatus::Ok);
  EXPECT_TRUE(m2.at("tst_02")->skipped_existing);
  EXPECT_EQ(m2.at("tst_02")->status, BatchClipStatus::Skipped);
  EXPECT_GT(m2.at("tst_02")->frames, 0);  // the previous summary's figures carry over
  EXPECT_EQ(m2.at("tst_02")->frames, by_stem(s1).at("tst_02")->frames);
  EXPECT_EQ(m2.at("tst_02")->reference_stem, by_stem(s1).at("tst_02")->reference_stem);
  EXPECT_EQ(m2.at("tst_bad")->status, BatchClipStatus::Failed);  // failed clips are retried
  EXPECT_EQ(fs::last_write_time(out.path() / "tst_02.bvh"), mtime);
  EXPECT_EQ(slurp(out.path() / "pairs.csv"), pairs1);
  EXPECT_FALSE(has_temporaries(out.path()));
  EXPECT_TRUE(contains(log2.str(), "skipped")) << log2.str();

  // --force redoes them all, byte-identically.
  o.force = true;
  std::ostringstream log3;
  const BatchSummary s3 = batch_run(o, Config{}, log3);
  EXPECT_EQ(s3.skipped, 0);
  EXPECT_EQ(s3.ok, 5);
  EXPECT_EQ(slurp(out.path() / "tst_02.bvh"), first);
}

TEST_F(BatchData, CancelledRunLeavesNoPartialOutputAndResumes) {
  TempDir out;
  BatchOptions o = options(out.path().string());
  std::atomic<bool> cancel{true};
  o.cancel = &cancel;
  std::ostringstream log;
  const BatchSummary s = batch_run(o, Config{}, log);
  EXPECT_TRUE(s.interrupted);
  EXPECT_EQ(s.cancelled, 6);
  for (const BatchClipResult& c : s.clips) EXPECT_EQ(c.status, BatchClipStatus::Cancelled);
  EXPECT_TRUE(fs::exists(out.path() / "pairs.csv"));
  EXPECT_TRUE(fs::exists(out.path() / "summary.json"));
  EXPECT_FALSE(fs::exists(out.path() / "tst_01.bvh"));
  cancel = false;
  const BatchSummary s2 = batch_run(o, Config{}, log);
  EXPECT_FALSE(s2.interrupted);
  EXPECT_EQ(s2.ok + s2.failed, 6);
  EXPECT_EQ(s2.skipped, 0);
}

TEST_F(BatchData, ManifestPairingAndClipManifests) {
  TempDir out, work;
  // Clip manifests with relative paths (relative to the manifest's folder).
  const fs::path pm = root() / "pool_manifest.csv";
  write_text(pm.string(),
             "# reference clips\nstem,bvh,wav,transcript\n"
             "A,pool/bvh/ref_a.bvh,pool/wav/ref_a.wav,pool/tsv/ref_a.tsv\n"
             "\"B\",pool/bvh/ref_b.bvh,pool/wav/ref_b.wav,none\n"
             "missing,pool/bvh/nope.bvh,pool/wav/nope.wav,\n");
  const fs::path tm = root() / "test_manifest.csv";
  write_text(tm.string(),
             "wav,transcript\r\n"
             "tests_flat/tst_01.wav,tests_flat/tst_01.tsv\r\n"
             "tests_flat/tst_02.wav,\r\n"
             "tests_flat/tst_03.wav,tests_flat/tst_03.tsv\r\n"
             "tests_flat/tst_04.wav,tests_flat/tst_04.tsv\r\n"
             "tests_flat/tst_05.wav,tests_flat/tst_05.tsv\r\n");
  const std::string pairs = work.file("pairs.csv");
  write_text(pairs, "test_stem,reference_stem\ntst_01,A\ntst_02,B\ntst_03,missing\ntst_04,nobody\n");
  BatchOptions o;
  o.pool_manifests = {pm.string()};
  o.test_manifests = {tm.string()};
  o.output_dir = out.path().string();
  o.pairs_manifest = pairs;
  o.progress = BatchProgress::Quiet;
  std::ostringstream log;
  const BatchSummary s = batch_run(o, Config{}, log);
  const auto m = by_stem(s);
  EXPECT_EQ(m.at("tst_01")->status, BatchClipStatus::Ok);
  EXPECT_EQ(m.at("tst_01")->reference_stem, "A");
  EXPECT_EQ(m.at("tst_02")->status, BatchClipStatus::Ok);
  EXPECT_EQ(m.at("tst_03")->status, BatchClipStatus::Failed);  // reference files missing
  EXPECT_TRUE(contains(m.at("tst_03")->error, "nope.bvh")) << m.at("tst_03")->error;
  EXPECT_EQ(m.at("tst_04")->status, BatchClipStatus::Failed);
  EXPECT_TRUE(contains(m.at("tst_04")->error, "not in the pool")) << m.at("tst_04")->error;
  EXPECT_EQ(m.at("tst_05")->status, BatchClipStatus::Failed);
  EXPECT_TRUE(contains(m.at("tst_05")->error, "not paired")) << m.at("tst_05")->error;
  EXPECT_TRUE(log.str().empty());

  // The pairs.csv a run writes is a manifest for the next one.
  TempDir out2;
  BatchOptions o2 = options(out2.path().string());
  o2.seed = 3;
  batch_run(o2, Config{}, log);
  TempDir out3;
  BatchOptions o3 = options(out3.path().string());
  o3.pairing = BatchPairing::Manifest;
  o3.pairs_manifest = (out2.path() / "pairs.csv").string();
  o3.seed = 3;
  const BatchSummary s3 = batch_run(o3, Config{}, log);
  EXPECT_EQ(slurp(out3.path() / "pairs.csv"), slurp(out2.path() / "pairs.csv"));
  for (const BatchClipResult& c : s3.clips)
    if (c.status == BatchClipStatus::Ok) {
      EXPECT_EQ(slurp(out3.path() / (c.test_stem + ".bvh")), slurp(out2.path() / (c.test_stem + ".bvh")));
    }

  // A manifest naming an unknown test clip is a setup error.
  write_text(pairs, "tst_01,A\nno_such_test,A\n");
  EXPECT_THROW(batch_run(o, Config{}, log), Error);
}

TEST_F(BatchData, SetupErrors) {
  TempDir out;
  std::ostringstream log;
  auto message = [&](const BatchOptions& o) -> std::string {
    try {
      batch_run(o, Config{}, log);
    } catch (const Error& e) {
      return e.what();
    }
    return "<no error>";
  };
  BatchOptions o = options(out.path().string());
  o.pool_dirs.clear();
  EXPECT_TRUE(contains(message(o), "pool")) << message(o);
  o = options(out.path().string());
  o.pool_dirs = {tests_flat() + "/nowhere"};
  EXPECT_TRUE(contains(message(o), "nowhere")) << message(o);
  o = options(out.path().string());
  o.blacklist = out.file("bl.txt");
  write_text(o.blacklist, "ref_a\nref_b\nref_c\nref_broken\n");
  EXPECT_TRUE(contains(message(o), "empty after the blacklist")) << message(o);
  o = options(out.path().string());
  o.pool_dirs = {pool(), pool()};
  EXPECT_TRUE(contains(message(o), "given twice")) << message(o);
  o = options(tests_flat());
  EXPECT_TRUE(contains(message(o), "input folder")) << message(o);
  o = options(out.path().string());
  o.pairing = BatchPairing::Manifest;
  EXPECT_TRUE(contains(message(o), "--manifest")) << message(o);
  o = options(out.path().string());
  o.jobs = -1;
  EXPECT_TRUE(contains(message(o), "--jobs")) << message(o);
}

// Runs `gmg batch ...` in-process through add_batch_command; returns the exit code.
int run_cli(std::vector<std::string> args) {
  CLI::App app{"gmg"};
  app.require_subcommand(1);
  int code = -1;
  add_batch_command(app, &code);
  args.insert(args.begin(), "gmg");
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (std::string& a : args) argv.push_back(a.data());
  app.parse(static_cast<int>(argv.size()), argv.data());
  return code;
}

TEST_F(BatchData, CommandLineExitCodes) {
  TempDir out1, out2, out3;
  // Good clips only: exit 0. --set reaches the engine (blend length in the reports).
  const std::string tm = out3.file("tests.csv");
  write_text(tm, "stem,wav,transcript\n" + std::string("t1,") + tests_flat() + "/tst_01.wav," + tests_flat() +
                     "/tst_01.tsv\nt2," + tests_flat() + "/tst_02.wav,\n");
  const std::string bl = out3.file("bl.txt");
  write_text(bl, "ref_broken\n");
  EXPECT_EQ(run_cli({"batch", "--pool", pool(), "--test-manifest", tm, "-o", out1.path().string(), "--blacklist", bl,
                     "--seed", "5", "--jobs", "2", "--set", "l_blend=6", "--reports", "--progress", "lines"}),
            0);
  EXPECT_TRUE(fs::exists(out1.path() / "t1.bvh"));
  const auto report = nlohmann::json::parse(slurp(out1.path() / "t2.json"));
  EXPECT_EQ(report["seed"], 5);
  EXPECT_EQ(report["parameters"]["l_blend"], 6);
  // A broken test clip: exit 1.
  EXPECT_EQ(run_cli({"batch", "--pool", pool(), "--tests", tests_flat(), "-o", out2.path().string(), "--blacklist", bl,
                     "--progress", "none"}),
            1);
  // Setup error: exit 2.
  EXPECT_EQ(run_cli({"batch", "--pool", out3.path().string(), "--tests", tests_flat(), "-o", out2.path().string()}), 2);
  EXPECT_EQ(
      run_cli({"batch", "--pool", pool(), "--tests", tests_flat(), "-o", out3.path().string(), "--set", "nokey=1"}), 2);
}

// What the pipeline warns about reaches batch's progress lines: here a pool clip whose audio (6.5 s)
// is not its motion's (20 s).
TEST_F(BatchData, WarningsOfTheReferencesAndClipsAreProgressLines) {
  TempDir work;
  const std::string manifest = work.file("pool.csv");
  write_text(manifest,
             "stem,bvh,wav,transcript\nmixed," + pool() + "/bvh/ref_a.bvh," + tests_flat() + "/tst_01.wav,\n");
  BatchOptions o = options(work.file("out"));
  o.pool_dirs.clear();
  o.pool_manifests = {manifest};
  o.test_dirs.clear();
  o.test_manifests = {work.file("tests.csv")};
  write_text(work.file("tests.csv"), "stem,wav,transcript\nt2," + tests_flat() + "/tst_02.wav,\n");
  std::ostringstream log;
  const BatchSummary s = batch_run(o, Config{}, log);
  EXPECT_EQ(s.ok, 1) << log.str();
  EXPECT_TRUE(contains(log.str(), "batch: warning: " + tests_flat() + "/tst_01.wav: lasts 6.5 s but its motion " +
                                      pool() + "/bvh/ref_a.bvh lasts 20.0 s"))
      << log.str();
}

TEST_F(BatchData, TerminalProgressIsOneUpdatingLine) {
  TempDir out;
  BatchOptions o = options(out.path().string());
  o.progress = BatchProgress::Terminal;
  o.jobs = 1;
  std::ostringstream log;
  batch_run(o, Config{}, log);
  const std::string s = log.str();
  EXPECT_TRUE(contains(s, "\r\x1b[K[")) << s;
  EXPECT_TRUE(contains(s, " ok ")) << s;
  EXPECT_TRUE(contains(s, "FAILED")) << s;
}

// Files that used to vanish without a word: a broken symbolic link and a transcript without audio
// are failed clips with their reason in summary.csv and summary.json; a broken link in the pool is
// a note there; a FLAC test clip (made with ffmpeg, when it is installed) is read like a WAV.
TEST_F(BatchData, BrokenLinksAndIncompleteClipsAreReportedNotSkipped) {
  TempDir work, out;
  const fs::path p = work.path() / "pool", t = work.path() / "tests";
  fs::create_directories(p);
  fs::create_directories(t);
  for (const char* ext : {"bvh", "wav", "tsv"})
    fs::copy_file(root() / "pool" / ext / (std::string("ref_a.") + ext), p / (std::string("ref_a.") + ext));
  fs::create_symlink(work.path() / "gone.bvh", p / "ref_link.bvh");
  fs::copy_file(p / "ref_a.wav", p / "ref_link.wav");
  for (const char* ext : {"wav", "tsv"})
    fs::copy_file(root() / "tests_flat" / (std::string("tst_01.") + ext), t / (std::string("tst_01.") + ext));
  fs::create_symlink(work.path() / "moved.wav", t / "tst_link.wav");
  fs::copy_file(t / "tst_01.tsv", t / "tst_only.tsv");                    // its WAV is missing
  fs::copy_file(root() / "tests_flat" / "tst_02.bvh", t / "tst_gt.bvh");  // ground truth alone: not a clip
  const bool flac = std::system("ffmpeg -version > /dev/null 2>&1") == 0;
  std::string pairs = "tst_01,ref_a\n";
  if (flac) {
    const std::string cmd = "ffmpeg -hide_banner -loglevel error -y -i '" + (t / "tst_01.wav").string() + "' '" +
                            (t / "tst_flac.flac").string() + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    pairs += "tst_flac,ref_a\n";
  }
  write_text(work.file("pairs.csv"), pairs);
  BatchOptions o = options(out.path().string());
  o.pool_dirs = {p.string()};
  o.test_dirs = {t.string()};
  o.pairs_manifest = work.file("pairs.csv");
  std::ostringstream log;
  const BatchSummary s = batch_run(o, Config{}, log);
  const auto m = by_stem(s);
  ASSERT_EQ(m.size(), flac ? 4u : 3u) << log.str();
  EXPECT_EQ(m.count("tst_gt"), 0u);
  EXPECT_EQ(m.at("tst_01")->status, BatchClipStatus::Ok) << m.at("tst_01")->error;
  if (flac) {
    EXPECT_EQ(m.at("tst_flac")->status, BatchClipStatus::Ok) << m.at("tst_flac")->error;
    EXPECT_EQ(slurp(out.path() / "tst_flac.bvh"), slurp(out.path() / "tst_01.bvh"));  // the same samples
  }
  const std::string link_error =
      (t / "tst_link.wav").string() + " is a broken symbolic link (to " + (work.path() / "moved.wav").string() + ")";
  EXPECT_EQ(m.at("tst_link")->status, BatchClipStatus::Failed);
  EXPECT_EQ(m.at("tst_link")->error, link_error);
  EXPECT_EQ(m.at("tst_only")->status, BatchClipStatus::Failed);
  EXPECT_EQ(m.at("tst_only")->error,
            "the transcript " + (t / "tst_only.tsv").string() + " has no audio (WAV) beside it");
  const std::string pool_note = "pool: " + (p / "ref_link.bvh").string() + " is a broken symbolic link (to " +
                                (work.path() / "gone.bvh").string() + ")";
  EXPECT_TRUE(contains(log.str(), "batch: note: " + pool_note)) << log.str();

  const auto summary = nlohmann::json::parse(slurp(out.path() / "summary.json"));
  EXPECT_EQ(summary["notes"], nlohmann::json::array({pool_note}));
  EXPECT_EQ(summary["counts"]["failed"], 2);
  bool listed = false;
  for (const auto& c : summary["clips"])
    if (c["test"] == "tst_link") listed = c["status"] == "failed" && c["error"] == link_error;
  EXPECT_TRUE(listed) << summary.dump(2);
  EXPECT_TRUE(contains(slurp(out.path() / "summary.csv"), "tst_only,,failed,")) << slurp(out.path() / "summary.csv");
}

}  // namespace
}  // namespace gmg
