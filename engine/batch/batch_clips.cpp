// Clip discovery: clip folders (flat or GENEA-style subfolders) and clip manifests (batch.h).
#include <algorithm>
#include <set>

#include "engine/batch/batch_internal.h"
#include "engine/core/csv.h"
#include "engine/core/error.h"
#include "engine/core/strings.h"

namespace gmg::batch {
namespace {

// The files of one stem found in a folder.
struct StemFiles {
  std::string bvh, wav, tsv, textgrid, json;
  std::string audio;   // speech in another format (FLAC, MP3, ...), used when there is no .wav
  std::string broken;  // why a file of the stem is unusable (a broken symbolic link), "" = fine
};

// Audio formats other than WAV that read_audio decodes (audio/audio_file.h).
bool is_other_audio(const std::string& ext) {
  static const std::set<std::string> exts = {".flac", ".mp3", ".ogg", ".oga", ".opus", ".m4a", ".aac", ".aif", ".aiff"};
  return exts.count(ext) > 0;
}

using StemMap = std::map<std::string, StemFiles>;

// The field of a file by its extension (any case); nullptr for a file batch does not use.
std::string StemFiles::*slot_of(const fs::path& p) {
  const std::string ext = ascii_lower(p.extension().string());
  if (ext == ".bvh") return &StemFiles::bvh;
  if (ext == ".wav") return &StemFiles::wav;
  if (ext == ".tsv") return &StemFiles::tsv;
  if (ext == ".textgrid") return &StemFiles::textgrid;
  if (ext == ".json") return &StemFiles::json;
  if (is_other_audio(ext)) return &StemFiles::audio;
  return nullptr;
}

// A symbolic link whose target does not exist: `is_regular_file` says no, and the clip would
// vanish without a word. Kept as a file of its stem, with the reason.
bool is_broken_link(const fs::directory_entry& e, std::string* why) {
  std::error_code ec;
  if (!e.is_symlink(ec) || ec || fs::exists(e.path(), ec)) return false;
  const fs::path target = fs::read_symlink(e.path(), ec);
  *why = e.path().string() + " is a broken symbolic link" + (ec ? "" : " (to " + target.string() + ")");
  return true;
}

// Sorted, so discovery (and any "given twice" message) does not depend on the file system.
// Broken symbolic links are listed too, each with its reason in *broken.
std::vector<fs::path> sorted_regular_files(const fs::path& dir, std::map<fs::path, std::string>* broken) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code ec2;
    std::string why;
    if (it->is_regular_file(ec2)) {
      files.push_back(it->path());
    } else if (is_broken_link(*it, &why)) {
      files.push_back(it->path());
      (*broken)[it->path()] = why;
    }
  }
  if (ec) throw Error(dir.string() + ": cannot list folder (" + ec.message() + ")");
  std::sort(files.begin(), files.end());
  return files;
}

void scan_files(const fs::path& dir, StemMap& out) {
  std::map<fs::path, std::string> broken;
  for (const fs::path& p : sorted_regular_files(dir, &broken)) {
    const std::string name = p.filename().string();
    if (name.empty() || name[0] == '.') continue;
    std::string StemFiles::*const slot = slot_of(p);
    if (!slot) continue;
    StemFiles& f = out[p.stem().string()];
    std::string& s = f.*slot;
    if (!s.empty())
      throw Error("clip '" + p.stem().string() + "' has two " +
                  (slot == &StemFiles::audio ? std::string("audio") : ascii_lower(p.extension().string())) +
                  " files: " + s + " and " + p.string());
    s = p.string();
    if (broken.count(p) && f.broken.empty()) f.broken = broken[p];
  }
}

// Every stem of a clip folder: flat files and the GENEA-style subfolders.
StemMap scan_clip_folder(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(dir + ": not a folder");
  StemMap out;
  scan_files(dir, out);
  static const std::set<std::string> subfolders = {"bvh",  "wav",        "tsv",        "textgrid",
                                                   "json", "transcript", "transcripts"};
  std::vector<fs::path> subs;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code ec2;
    if (it->is_directory(ec2) && subfolders.count(ascii_lower(it->path().filename().string())))
      subs.push_back(it->path());
  }
  std::sort(subs.begin(), subs.end());
  for (const fs::path& s : subs) scan_files(s, out);
  return out;
}

std::string pick_transcript(const StemFiles& f) {
  if (!f.tsv.empty()) return f.tsv;
  if (!f.textgrid.empty()) return f.textgrid;
  return f.json;
}

// The speech of a stem: its WAV, else its audio in another format (with a note when both exist,
// so the other file is not left out without a word).
std::string pick_audio(const std::string& stem, const StemFiles& f, Clips& clips) {
  if (!f.wav.empty() && !f.audio.empty())
    clips.notes.push_back("clip '" + stem + "': " + f.audio + " not used: " + f.wav + " is read");
  return f.wav.empty() ? f.audio : f.wav;
}

// Outputs are named OUTDIR/<stem>.bvh and .json, so a stem must be a plain file name: with a '/'
// ("../escaped") the output would land outside OUTDIR.
bool is_plain_stem(const std::string& stem) {
  return !stem.empty() && stem != "." && stem != ".." && stem.find('/') == std::string::npos &&
         stem.find('\0') == std::string::npos;
}

void add_clip(ClipMap& clips, ClipFiles c, const char* role) {
  auto [it, inserted] = clips.emplace(c.stem, c);
  if (!inserted)
    throw Error(std::string(role) + " clip '" + c.stem + "' is given twice: in " + it->second.origin + " and in " +
                c.origin);
}

std::string resolve(const fs::path& base, const std::string& p) {
  if (p.empty()) return p;
  fs::path q(p);
  if (q.is_relative()) q = base / q;
  return q.lexically_normal().string();
}

// Column indices of a clip manifest's header row (-1 when absent).
struct ManifestColumns {
  int stem = -1, bvh = -1, wav = -1, transcript = -1;
};

ManifestColumns manifest_columns(const CsvRow& header, const std::string& path, bool pool) {
  ManifestColumns c;
  for (std::size_t i = 0; i < header.fields.size(); ++i) {
    const std::string h = ascii_lower(trim(header.fields[i]));
    const int idx = static_cast<int>(i);
    if (h == "stem" || h == "name" || h == "id")
      c.stem = idx;
    else if (h == "bvh" || h == "motion")
      c.bvh = idx;
    else if (h == "wav" || h == "audio")
      c.wav = idx;
    else if (h == "transcript" || h == "tsv" || h == "textgrid")
      c.transcript = idx;
  }
  if (c.wav < 0 || (pool && c.bvh < 0)) {
    std::string found;
    for (const std::string& f : header.fields) found += (found.empty() ? "" : ",") + f;
    throw Error(error_at_line(path, header.line,
                              std::string("the header row must name the columns (") +
                                  (pool ? "stem,bvh,wav,transcript" : "stem,wav,transcript") + "), found '" + found +
                                  "'"));
  }
  return c;
}

ClipFiles manifest_clip(const CsvRow& row, const ManifestColumns& col, const std::string& path, bool pool) {
  const fs::path base = fs::path(path).parent_path();
  auto get = [&](int c) { return c >= 0 && c < static_cast<int>(row.fields.size()) ? row.fields[c] : std::string(); };
  ClipFiles c;
  c.origin = path + ":" + std::to_string(row.line);
  c.wav = resolve(base, get(col.wav));
  if (pool) c.bvh = resolve(base, get(col.bvh));
  const std::string tr = get(col.transcript);
  c.transcript = ascii_lower(tr) == "none" ? "" : resolve(base, tr);
  c.stem = get(col.stem);
  if (c.wav.empty()) throw Error(error_at_line(path, row.line, "no WAV file given"));
  if (pool && c.bvh.empty()) throw Error(error_at_line(path, row.line, "no BVH file given"));
  if (c.stem.empty()) c.stem = fs::path(pool ? c.bvh : c.wav).stem().string();
  if (!is_plain_stem(c.stem))
    throw Error(error_at_line(
        path, row.line,
        "stem '" + c.stem + "' is not a plain file name (outputs are named after it inside the output folder)"));
  return c;
}

// Reads a clip manifest (see batch.h). pool = true needs a bvh column.
void read_clip_manifest(const std::string& path, bool pool, ClipMap& clips) {
  const std::vector<CsvRow> rows = csv_read_file(path);
  if (rows.empty()) throw Error(path + ": empty manifest (a header row naming the columns is needed)");
  const ManifestColumns columns = manifest_columns(rows[0], path, pool);
  for (std::size_t r = 1; r < rows.size(); ++r)
    add_clip(clips, manifest_clip(rows[r], columns, path, pool), pool ? "pool" : "test");
}

void add_pool_folder(const std::string& dir, Clips& clips) {
  for (const auto& [stem, f] : scan_clip_folder(dir)) {
    if (f.bvh.empty()) {  // audio alone is a test clip; a transcript alone is a clip missing its files
      if (f.wav.empty() && f.audio.empty() && !pick_transcript(f).empty())
        clips.notes.push_back("pool: " + pick_transcript(f) + " has no BVH and no audio beside it; not used");
      continue;
    }
    const std::string audio = pick_audio(stem, f, clips);
    if (audio.empty()) {
      clips.notes.push_back("pool: " + f.bvh + " has no audio (WAV) beside it; not used");
      continue;
    }
    // A broken link stays in the pool: the clips that draw it fail with the reason.
    if (!f.broken.empty()) clips.notes.push_back("pool: " + f.broken);
    add_clip(clips.pool, ClipFiles{stem, f.bvh, audio, pick_transcript(f), dir}, "pool");
  }
}

void add_test_folder(const std::string& dir, Clips& clips) {
  for (const auto& [stem, f] : scan_clip_folder(dir)) {
    const std::string audio = pick_audio(stem, f, clips), transcript = pick_transcript(f);
    std::string error = f.broken;
    if (audio.empty()) {
      if (transcript.empty()) continue;  // a BVH alone beside the tests (ground truth) is not a test clip
      error = "the transcript " + transcript + " has no audio (WAV) beside it";
    }
    add_clip(clips.tests, ClipFiles{stem, "", audio, transcript, dir, error}, "test");
  }
}

}  // namespace

ClipMap collect_reference_clips(const std::vector<std::string>& dirs, const std::vector<std::string>& manifests,
                                std::vector<std::string>& notes) {
  Clips clips;
  for (const std::string& dir : dirs) add_pool_folder(dir, clips);
  for (const std::string& m : manifests) read_clip_manifest(m, true, clips.pool);
  notes.insert(notes.end(), clips.notes.begin(), clips.notes.end());
  return clips.pool;
}

Clips collect_clips(const BatchOptions& options) {
  Clips clips;
  if (options.graph.empty()) {
    clips.pool = collect_reference_clips(options.pool_dirs, options.pool_manifests, clips.notes);
  } else {
    const std::string stem = fs::path(options.graph).stem().string();
    clips.pool.emplace(stem, ClipFiles{stem, options.graph, "", "", "--graph"});
  }
  for (const std::string& dir : options.test_dirs) add_test_folder(dir, clips);
  for (const std::string& m : options.test_manifests) read_clip_manifest(m, false, clips.tests);
  // Name where gmg looked: "pool/" or "a, b and 2 more".
  auto places = [](const std::vector<std::string>& dirs, const std::vector<std::string>& manifests) {
    std::vector<std::string> all = dirs;
    all.insert(all.end(), manifests.begin(), manifests.end());
    std::string text;
    for (std::size_t i = 0; i < all.size() && i < 3; ++i) text += (i == 0 ? "" : ", ") + all[i];
    if (all.size() > 3) text += " and " + std::to_string(all.size() - 3) + " more";
    return text.empty() ? std::string("(no --pool or --pool-manifest given)") : text;
  };
  if (clips.pool.empty())
    throw Error(places(options.pool_dirs, options.pool_manifests) +
                ": the pool holds no reference clip (a BVH and a WAV with the same stem)");
  if (clips.tests.empty())
    throw Error(places(options.test_dirs, options.test_manifests) + ": no test clip found (a WAV file)");
  return clips;
}

}  // namespace gmg::batch
