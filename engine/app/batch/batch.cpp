#include "engine/app/batch/batch.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <deque>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include <signal.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "engine/motion/bvh.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/app/pipeline.h"

namespace gmg {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

std::string fixed(double v, int decimals) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(decimals) << v;
  return os.str();
}

// ---------------------------------------------------------------------------------------------
// CSV (RFC 4180 subset: comma separated, "quoted" fields with "" escapes, LF or CRLF).

struct CsvRow {
  long line = 0;  // line where the row starts
  std::vector<std::string> fields;
};

// Rows of a CSV text; blank lines and lines whose first character is '#' are skipped.
std::vector<CsvRow> csv_parse(const std::string& text, const std::string& path) {
  std::vector<CsvRow> rows;
  std::size_t i = 0;
  if (text.size() >= 3 && static_cast<unsigned char>(text[0]) == 0xEF && static_cast<unsigned char>(text[1]) == 0xBB &&
      static_cast<unsigned char>(text[2]) == 0xBF)
    i = 3;
  long line = 1;
  while (i < text.size()) {
    // Skip comment lines and blank lines.
    if (text[i] == '#' || text[i] == '\n' || text[i] == '\r') {
      while (i < text.size() && text[i] != '\n') ++i;
      if (i < text.size()) ++i;
      ++line;
      continue;
    }
    CsvRow row;
    row.line = line;
    std::string field;
    bool quoted = false, in_quotes = false, done = false;
    while (!done) {
      if (i >= text.size()) {
        if (in_quotes) throw Error(error_at_line(path, row.line, "unterminated quoted field"));
        done = true;
        break;
      }
      const char c = text[i];
      if (in_quotes) {
        if (c == '"') {
          if (i + 1 < text.size() && text[i + 1] == '"') {
            field += '"';
            i += 2;
          } else {
            in_quotes = false;
            ++i;
          }
        } else {
          if (c == '\n') ++line;
          field += c;
          ++i;
        }
        continue;
      }
      if (c == '"' && trim(field).empty() && !quoted) {
        field.clear();
        quoted = in_quotes = true;
        ++i;
      } else if (c == ',') {
        row.fields.push_back(quoted ? field : trim(field));
        field.clear();
        quoted = false;
        ++i;
      } else if (c == '\n' || c == '\r') {
        if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
        ++i;
        ++line;
        done = true;
      } else {
        if (!quoted) field += c;  // text after a closing quote is ignored unless it is a comma
        ++i;
      }
    }
    row.fields.push_back(quoted ? field : trim(field));
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos && (s.empty() || (s.front() != ' ' && s.back() != ' ')))
    return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string out;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i) out += ',';
    out += csv_field(fields[i]);
  }
  return out + "\n";
}

// ---------------------------------------------------------------------------------------------
// Clip discovery.

struct ClipFiles {
  std::string stem, bvh, wav, transcript;
  std::string origin;  // folder or "manifest:line", for messages
};

// The files of one stem found in a folder.
struct StemFiles {
  std::string bvh, wav, tsv, textgrid, json;
};

enum class FileKind { Bvh, Wav, Tsv, TextGrid, Json, Other };

FileKind file_kind(const fs::path& p) {
  const std::string ext = lower(p.extension().string());
  if (ext == ".bvh") return FileKind::Bvh;
  if (ext == ".wav") return FileKind::Wav;
  if (ext == ".tsv") return FileKind::Tsv;
  if (ext == ".textgrid") return FileKind::TextGrid;
  if (ext == ".json") return FileKind::Json;
  return FileKind::Other;
}

std::string& slot(StemFiles& f, FileKind k) {
  switch (k) {
    case FileKind::Bvh: return f.bvh;
    case FileKind::Wav: return f.wav;
    case FileKind::Tsv: return f.tsv;
    case FileKind::TextGrid: return f.textgrid;
    default: return f.json;
  }
}

void scan_files(const fs::path& dir, std::map<std::string, StemFiles>& out) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code ec2;
    if (it->is_regular_file(ec2)) files.push_back(it->path());
  }
  if (ec) throw Error(dir.string() + ": cannot list folder (" + ec.message() + ")");
  std::sort(files.begin(), files.end());
  for (const fs::path& p : files) {
    const std::string name = p.filename().string();
    if (name.empty() || name[0] == '.') continue;
    const FileKind k = file_kind(p);
    if (k == FileKind::Other) continue;
    std::string& s = slot(out[p.stem().string()], k);
    if (!s.empty())
      throw Error("clip '" + p.stem().string() + "' has two " + lower(p.extension().string()) + " files: " + s +
                  " and " + p.string());
    s = p.string();
  }
}

// Every stem of a clip folder: flat files and the GENEA-style subfolders.
std::map<std::string, StemFiles> scan_clip_folder(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(dir + ": not a folder");
  std::map<std::string, StemFiles> out;
  scan_files(dir, out);
  static const std::set<std::string> subfolders = {"bvh", "wav", "tsv", "textgrid", "json", "transcript", "transcripts"};
  std::vector<fs::path> subs;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code ec2;
    if (it->is_directory(ec2) && subfolders.count(lower(it->path().filename().string()))) subs.push_back(it->path());
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

void add_clip(std::map<std::string, ClipFiles>& clips, ClipFiles c, const char* role) {
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

// Reads a clip manifest (see batch.h). pool = true needs a bvh column.
void read_clip_manifest(const std::string& path, bool pool, std::map<std::string, ClipFiles>& clips) {
  const std::vector<CsvRow> rows = csv_parse(read_file_bytes(path), path);
  if (rows.empty()) throw Error(path + ": empty manifest (a header row naming the columns is needed)");
  int c_stem = -1, c_bvh = -1, c_wav = -1, c_tr = -1;
  for (std::size_t i = 0; i < rows[0].fields.size(); ++i) {
    const std::string h = lower(trim(rows[0].fields[i]));
    const int idx = static_cast<int>(i);
    if (h == "stem" || h == "name" || h == "id") c_stem = idx;
    else if (h == "bvh" || h == "motion") c_bvh = idx;
    else if (h == "wav" || h == "audio") c_wav = idx;
    else if (h == "transcript" || h == "tsv" || h == "textgrid") c_tr = idx;
  }
  if (c_wav < 0 || (pool && c_bvh < 0)) {
    std::string found;
    for (const std::string& f : rows[0].fields) found += (found.empty() ? "" : ",") + f;
    throw Error(error_at_line(path, rows[0].line,
                              std::string("the header row must name the columns (") +
                                  (pool ? "stem,bvh,wav,transcript" : "stem,wav,transcript") + "), found '" + found +
                                  "'"));
  }
  const fs::path base = fs::path(path).parent_path();
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const CsvRow& row = rows[r];
    auto get = [&](int c) { return c >= 0 && c < static_cast<int>(row.fields.size()) ? row.fields[c] : std::string(); };
    ClipFiles c;
    c.origin = path + ":" + std::to_string(row.line);
    c.wav = resolve(base, get(c_wav));
    if (pool) c.bvh = resolve(base, get(c_bvh));
    const std::string tr = get(c_tr);
    c.transcript = lower(tr) == "none" ? "" : resolve(base, tr);
    c.stem = get(c_stem);
    if (c.wav.empty()) throw Error(error_at_line(path, row.line, "no WAV file given"));
    if (pool && c.bvh.empty()) throw Error(error_at_line(path, row.line, "no BVH file given"));
    if (c.stem.empty()) c.stem = fs::path(pool ? c.bvh : c.wav).stem().string();
    add_clip(clips, std::move(c), pool ? "pool" : "test");
  }
}

// ---------------------------------------------------------------------------------------------
// Blacklist and pairs manifest.

std::string stem_of_listed(std::string s) {
  const std::size_t slash = s.find_last_of("/\\");
  if (slash != std::string::npos) s = s.substr(slash + 1);
  const std::size_t dot = s.find_last_of('.');
  if (dot != std::string::npos) {
    const std::string ext = lower(s.substr(dot));
    if (ext == ".bvh" || ext == ".wav" || ext == ".tsv" || ext == ".textgrid" || ext == ".json") s.resize(dot);
  }
  return s;
}

std::set<std::string> read_blacklist(const std::string& path) {
  std::set<std::string> out;
  std::istringstream in(read_file_bytes(path));
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    line = trim(line);
    if (line.size() >= 3 && static_cast<unsigned char>(line[0]) == 0xEF) line = trim(line.substr(3));  // BOM
    if (!line.empty()) out.insert(stem_of_listed(line));
  }
  return out;
}

// test stem -> reference stem. With `strict`, malformed rows are errors; otherwise skipped.
std::map<std::string, std::string> read_pairs(const std::string& path, bool strict) {
  std::map<std::string, std::string> out;
  std::vector<CsvRow> rows = csv_parse(read_file_bytes(path), path);
  std::size_t first = 0;
  if (!rows.empty() && rows[0].fields.size() >= 2) {
    const std::string a = lower(rows[0].fields[0]), b = lower(rows[0].fields[1]);
    if ((a == "test_stem" || a == "test") && (b == "reference_stem" || b == "reference")) first = 1;
  }
  for (std::size_t r = first; r < rows.size(); ++r) {
    const CsvRow& row = rows[r];
    if (row.fields.size() < 2 || row.fields[0].empty() || row.fields[1].empty()) {
      if (strict) throw Error(error_at_line(path, row.line, "expected 'test_stem,reference_stem'"));
      continue;
    }
    auto [it, inserted] = out.emplace(row.fields[0], row.fields[1]);
    if (!inserted && it->second != row.fields[1]) {
      if (strict)
        throw Error(error_at_line(path, row.line, "test clip '" + row.fields[0] + "' is paired twice ('" +
                                                      it->second + "' and '" + row.fields[1] + "')"));
      it->second = row.fields[1];
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Progress display.

class Progress {
 public:
  Progress(std::ostream& os, BatchProgress mode) : os_(os) {
    if (mode == BatchProgress::Auto) {
      if (&os == &std::cerr || &os == &std::clog) fd_ = 2;
      else if (&os == &std::cout) fd_ = 1;
      terminal_ = fd_ >= 0 && ::isatty(fd_) != 0;
    } else {
      terminal_ = mode == BatchProgress::Terminal;
      quiet_ = mode == BatchProgress::Quiet;
    }
  }

  // A line that stays.
  void line(const std::string& s) {
    if (quiet_) return;
    std::lock_guard<std::mutex> lock(m_);
    if (terminal_) {
      os_ << "\r\x1b[K" << s << "\n";
      if (!status_.empty()) os_ << status_;
    } else {
      os_ << s << "\n";
    }
    os_.flush();
  }

  // The updating status line (on a terminal), else `plain` as a line.
  void status(const std::string& short_text, const std::string& plain) {
    if (quiet_) return;
    std::lock_guard<std::mutex> lock(m_);
    if (terminal_) {
      status_ = short_text;
      const std::size_t width = columns();
      if (width > 1 && status_.size() >= width) status_.resize(width - 1);
      os_ << "\r\x1b[K" << status_;
    } else {
      os_ << plain << "\n";
    }
    os_.flush();
  }

  void finish() {
    if (quiet_) return;
    std::lock_guard<std::mutex> lock(m_);
    if (terminal_ && !status_.empty()) os_ << "\n";
    status_.clear();
    os_.flush();
  }

 private:
  std::size_t columns() const {
    struct winsize w {};
    if (fd_ >= 0 && ::ioctl(fd_, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
    return 80;
  }

  std::ostream& os_;
  bool terminal_ = false, quiet_ = false;
  int fd_ = -1;
  std::mutex m_;
  std::string status_;
};

// ---------------------------------------------------------------------------------------------
// Stale temporary files of a killed run: "<name>.tmp<pid>_<n>" (write_file_atomically's names),
// removed when that process is gone.

void remove_stale_temporaries(const fs::path& dir, Progress& progress) {
  std::error_code ec;
  int removed = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::size_t pos = name.rfind(".tmp");
    if (pos == std::string::npos || pos == 0) continue;
    const std::string base = lower(name.substr(0, pos));
    auto ends = [&](const char* e) {
      const std::string x(e);
      return base.size() > x.size() && base.compare(base.size() - x.size(), x.size(), x) == 0;
    };
    if (!ends(".bvh") && !ends(".json") && !ends(".csv")) continue;
    const std::string tail = name.substr(pos + 4);
    const std::size_t us = tail.find('_');
    if (us == std::string::npos || us == 0 || us + 1 >= tail.size()) continue;
    if (!std::all_of(tail.begin(), tail.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '_'; }))
      continue;
    long pid = 0;
    try {
      pid = std::stol(tail.substr(0, us));
    } catch (...) {
      continue;
    }
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM) continue;  // still running
    std::error_code ec2;
    if (fs::remove(it->path(), ec2)) ++removed;
  }
  if (removed) progress.line("batch: removed " + std::to_string(removed) + " temporary file(s) of an interrupted run");
}

// ---------------------------------------------------------------------------------------------
// Scheduling.

struct RefState {
  const ClipFiles* clip = nullptr;
  std::size_t result_index = 0;        // into BatchSummary::references
  std::deque<std::size_t> pending;     // clip indices not started
  int outstanding = 0;                 // clips not finished
  enum class State { Unbuilt, Building, Ready, Failed } state = State::Unbuilt;
  std::shared_ptr<const MotionGraph> graph;
  std::string error;
};

int fallback_total(const nlohmann::ordered_json& totals) {
  int n = 0;
  const auto it = totals.find("fallbacks");
  if (it == totals.end()) return 0;
  if (it->is_number()) return it->get<int>();
  if (it->is_object())
    for (const auto& v : *it)
      if (v.is_number()) n += v.get<int>();
  return n;
}

nlohmann::ordered_json summary_json(const BatchSummary& s, const BatchOptions& o, const std::string& pairing) {
  nlohmann::ordered_json j;
  j["tool"] = "gmg batch";
  j["seed"] = s.seed;
  j["pairing"] = pairing;
  j["blacklist"] = o.blacklist.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(o.blacklist);
  j["jobs"] = s.jobs;
  j["interrupted"] = s.interrupted;
  j["counts"] = {{"clips", s.clips.size()},     {"ok", s.ok},
                 {"failed", s.failed},          {"skipped", s.skipped},
                 {"cancelled", s.cancelled},    {"references", s.references.size()},
                 {"blacklisted", s.blacklisted}};
  j["seconds"] = s.seconds;
  j["graph_seconds"] = s.graph_seconds;
  nlohmann::ordered_json refs = nlohmann::ordered_json::array();
  for (const BatchReferenceResult& r : s.references) {
    refs.push_back({{"stem", r.stem},
                    {"motion", r.motion},
                    {"audio", r.audio},
                    {"transcript", r.transcript.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.transcript)},
                    {"clips", r.clips},
                    {"frames", r.frames},
                    {"build_seconds", r.build_seconds},
                    {"error", r.error.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.error)}});
  }
  j["references"] = refs;
  nlohmann::ordered_json clips = nlohmann::ordered_json::array();
  for (const BatchClipResult& c : s.clips) {
    clips.push_back({{"test", c.test_stem},
                     {"reference", c.reference_stem.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(c.reference_stem)},
                     {"status", c.status},
                     {"frames", c.frames},
                     {"fallbacks", c.fallbacks},
                     {"failures", c.failures},
                     {"seconds", c.seconds},
                     {"output", c.output.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(c.output)},
                     {"error", c.error.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(c.error)}});
  }
  j["clips"] = clips;
  return j;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

std::vector<std::string> batch_draw_references(const std::vector<std::string>& test_stems,
                                               const std::vector<std::string>& pool, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::string> out;
  out.reserve(test_stems.size());
  for (const std::string& t : test_stems) {
    const std::uint64_t r = rng();  // one draw per test clip, whatever happens
    const auto self = std::find(pool.begin(), pool.end(), t);
    const std::size_t n = pool.size() - (self != pool.end() ? 1 : 0);
    if (n == 0) {
      out.emplace_back();
      continue;
    }
    std::size_t k = static_cast<std::size_t>(r % n);
    if (self != pool.end() && k >= static_cast<std::size_t>(self - pool.begin())) ++k;  // skip the test itself
    out.push_back(pool[k]);
  }
  return out;
}

BatchSummary batch_run(const BatchOptions& options, const Config& config, std::ostream& progress_stream) {
  const Clock::time_point t_start = Clock::now();
  Progress progress(progress_stream, options.progress);
  BatchSummary summary;

  // ---- options ----
  if (options.output_dir.empty()) throw Error("batch: no output folder given (-o OUTDIR)");
  if (options.jobs < 0) throw Error("batch: --jobs must be 0 (all cores) or more, got " + std::to_string(options.jobs));
  std::string pairing = options.pairing;
  if (pairing.empty()) pairing = options.pairs_manifest.empty() ? "random" : "manifest";
  if (pairing != "random" && pairing != "manifest")
    throw Error("batch: --pairing must be 'random' or 'manifest', got '" + pairing + "'");
  if (pairing == "manifest" && options.pairs_manifest.empty())
    throw Error("batch: --pairing manifest needs --manifest pairs.csv");
  if (pairing == "random" && !options.pairs_manifest.empty())
    throw Error("batch: --manifest " + options.pairs_manifest + " given with --pairing random");
  if (options.pool_dirs.empty() && options.pool_manifests.empty())
    throw Error("batch: no pool of reference clips given (--pool DIR or --pool-manifest CSV)");
  if (options.test_dirs.empty() && options.test_manifests.empty())
    throw Error("batch: no test clips given (--tests DIR or --test-manifest CSV)");
  Config clip_config = config;
  if (options.seed) clip_config.seed = *options.seed;
  config_validate(clip_config);
  summary.seed = clip_config.seed;

  // ---- clips ----
  std::map<std::string, ClipFiles> pool, tests;
  std::vector<std::string> notes;
  for (const std::string& dir : options.pool_dirs) {
    for (const auto& [stem, f] : scan_clip_folder(dir)) {
      if (f.bvh.empty()) continue;  // a WAV alone is a test clip
      if (f.wav.empty()) {
        notes.push_back("pool: " + f.bvh + " has no WAV beside it; not used");
        continue;
      }
      add_clip(pool, ClipFiles{stem, f.bvh, f.wav, pick_transcript(f), dir}, "pool");
    }
  }
  for (const std::string& m : options.pool_manifests) read_clip_manifest(m, true, pool);
  for (const std::string& dir : options.test_dirs) {
    for (const auto& [stem, f] : scan_clip_folder(dir)) {
      if (f.wav.empty()) continue;
      add_clip(tests, ClipFiles{stem, "", f.wav, pick_transcript(f), dir}, "test");
    }
  }
  for (const std::string& m : options.test_manifests) read_clip_manifest(m, false, tests);
  if (pool.empty()) throw Error("batch: the pool holds no reference clip (a BVH and a WAV with the same stem)");
  if (tests.empty()) throw Error("batch: no test clip found (a WAV file)");

  std::set<std::string> blacklist;
  if (!options.blacklist.empty()) blacklist = read_blacklist(options.blacklist);
  std::vector<std::string> pool_stems;
  for (const auto& [stem, c] : pool) {
    if (blacklist.count(stem)) {
      ++summary.blacklisted;
      continue;
    }
    pool_stems.push_back(stem);
  }
  if (pool_stems.empty())
    throw Error("batch: the pool is empty after the blacklist (" + std::to_string(summary.blacklisted) +
                " clips blacklisted by " + options.blacklist + ")");

  // ---- output folder ----
  const fs::path out_dir(options.output_dir);
  {
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (!fs::is_directory(out_dir, ec)) throw Error(options.output_dir + ": cannot create the output folder");
    for (const std::vector<std::string>* dirs : {&options.pool_dirs, &options.test_dirs})
      for (const std::string& d : *dirs)
        for (const fs::path& p : {fs::path(d), fs::path(d) / "bvh", fs::path(d) / "wav"}) {
          std::error_code ec2;
          if (fs::exists(p, ec2) && fs::equivalent(p, out_dir, ec2))
            throw Error(options.output_dir + ": the output folder is an input folder; choose another");
        }
  }
  remove_stale_temporaries(out_dir, progress);

  // ---- pairing ----
  std::vector<std::string> test_stems;
  for (const auto& [stem, c] : tests) test_stems.push_back(stem);
  std::vector<std::string> refs(test_stems.size());
  std::vector<std::string> pair_errors(test_stems.size());
  if (pairing == "random") {
    refs = batch_draw_references(test_stems, pool_stems, clip_config.seed);
    for (std::size_t i = 0; i < refs.size(); ++i)
      if (refs[i].empty()) pair_errors[i] = "no reference clip to draw from (the pool holds only this clip)";
  } else {
    const std::map<std::string, std::string> pairs = read_pairs(options.pairs_manifest, true);
    for (const auto& [t, r] : pairs)
      if (!tests.count(t))
        throw Error(options.pairs_manifest + ": test clip '" + t + "' is not among the test clips");
    for (std::size_t i = 0; i < test_stems.size(); ++i) {
      const auto it = pairs.find(test_stems[i]);
      if (it == pairs.end()) {
        pair_errors[i] = "not paired in " + options.pairs_manifest;
        continue;
      }
      refs[i] = it->second;
      if (blacklist.count(it->second))
        pair_errors[i] = "reference '" + it->second + "' (from " + options.pairs_manifest + ") is blacklisted";
      else if (!pool.count(it->second))
        pair_errors[i] = "reference '" + it->second + "' (from " + options.pairs_manifest + ") is not in the pool";
    }
  }

  // ---- results, skipping finished clips ----
  std::map<std::string, std::string> previous_pairs;
  {
    std::error_code ec;
    const fs::path prev = out_dir / "pairs.csv";
    if (fs::exists(prev, ec)) {
      try {
        previous_pairs = read_pairs(prev.string(), false);
      } catch (const std::exception&) {
        // An unreadable old record is only lost information.
      }
    }
  }
  // The previous summary's figures of clips that will be skipped (so a resumed run's summary
  // still covers every clip).
  std::map<std::string, nlohmann::json> previous_clips;
  {
    std::error_code ec;
    const fs::path prev = out_dir / "summary.json";
    if (fs::exists(prev, ec)) {
      try {
        const nlohmann::json j = nlohmann::json::parse(read_file_bytes(prev.string()));
        for (const nlohmann::json& c : j.at("clips"))
          if (c.at("test").is_string()) previous_clips[c.at("test").get<std::string>()] = c;
      } catch (const std::exception&) {
      }
    }
  }
  summary.clips.resize(test_stems.size());
  int preset_done = 0;
  for (std::size_t i = 0; i < test_stems.size(); ++i) {
    BatchClipResult& c = summary.clips[i];
    c.test_stem = test_stems[i];
    c.reference_stem = refs[i];
    c.output = (out_dir / (test_stems[i] + ".bvh")).string();
    std::error_code ec;
    if (!options.force && fs::exists(c.output, ec)) {
      c.status = "skipped";
      c.skipped_existing = true;
      const auto it = previous_pairs.find(c.test_stem);
      if (it != previous_pairs.end()) c.reference_stem = it->second;
      const auto pc = previous_clips.find(c.test_stem);
      if (pc != previous_clips.end()) {
        const nlohmann::json& p = pc->second;
        const auto text = [&](const char* k) {
          return p.contains(k) && p[k].is_string() ? p[k].get<std::string>() : std::string();
        };
        const auto number = [&](const char* k) { return p.contains(k) && p[k].is_number() ? p[k].get<double>() : 0.0; };
        if ((text("status") == "ok" || text("status") == "skipped") && text("reference") == c.reference_stem) {
          c.frames = static_cast<int>(number("frames"));
          c.fallbacks = static_cast<int>(number("fallbacks"));
          c.failures = static_cast<int>(number("failures"));
          c.seconds = number("seconds");
        }
      }
      ++preset_done;
    } else if (!pair_errors[i].empty()) {
      c.status = "failed";
      c.error = pair_errors[i];
      c.output.clear();
      ++preset_done;
    }
  }

  // References: the eligible pool, with the clips that drew them.
  std::vector<RefState> ref_states(pool_stems.size());
  std::map<std::string, std::size_t> ref_index;
  for (std::size_t k = 0; k < pool_stems.size(); ++k) {
    const ClipFiles& f = pool.at(pool_stems[k]);
    ref_index[f.stem] = k;
    ref_states[k].clip = &f;
    ref_states[k].result_index = k;
    summary.references.push_back(BatchReferenceResult{f.stem, f.bvh, f.wav, f.transcript, 0, 0, 0.0, ""});
  }
  std::size_t to_do = 0;
  for (std::size_t i = 0; i < summary.clips.size(); ++i) {
    if (!summary.clips[i].status.empty()) continue;
    RefState& r = ref_states.at(ref_index.at(summary.clips[i].reference_stem));
    r.pending.push_back(i);
    ++r.outstanding;
    ++summary.references[r.result_index].clips;
    ++to_do;
  }

  // pairs.csv first, so the pairing is on record even if the run is interrupted.
  write_file_atomically((out_dir / "pairs.csv").string(), [&](std::ostream& os) {
    os << csv_line({"test_stem", "reference_stem"});
    for (const BatchClipResult& c : summary.clips)
      if (!c.reference_stem.empty()) os << csv_line({c.test_stem, c.reference_stem});
  });

  unsigned jobs = options.jobs > 0 ? static_cast<unsigned>(options.jobs) : std::thread::hardware_concurrency();
  if (jobs == 0) jobs = 1;
  summary.jobs = static_cast<int>(jobs);
  const std::size_t worker_count = std::min<std::size_t>(jobs, std::max<std::size_t>(to_do, 1));

  for (const std::string& n : notes) progress.line("batch: note: " + n);
  {
    std::ostringstream os;
    os << "batch: " << test_stems.size() << " test clips";
    if (preset_done) os << " (" << summary.clips.size() - to_do << " skipped or unpaired)";
    os << ", pool of " << pool_stems.size() << " reference clips";
    if (summary.blacklisted) os << " (" << summary.blacklisted << " blacklisted)";
    os << ", pairing " << pairing << ", seed " << clip_config.seed << ", " << jobs << (jobs == 1 ? " job" : " jobs");
    progress.line(os.str());
  }
  const std::size_t total = summary.clips.size();
  std::size_t finished = 0;
  std::mutex m;  // guards ref_states, finished, summary.references
  {
    int skipped = 0;
    for (const BatchClipResult& c : summary.clips) {
      if (c.status == "skipped") ++skipped;
      if (c.status == "failed") {
        ++finished;
        progress.line("[" + std::to_string(finished) + "/" + std::to_string(total) + "] " + c.test_stem +
                      " FAILED: " + c.error);
      }
    }
    finished += static_cast<std::size_t>(skipped);
    if (skipped)
      progress.line("batch: " + std::to_string(skipped) + " clip(s) skipped: output exists (--force redoes them)");
  }

  auto cancelled = [&] { return options.cancel && options.cancel->load(); };
  std::condition_variable cv;
  std::size_t pending_total = to_do;

  auto run_clip = [&](std::size_t i, const RefState& r, std::shared_ptr<const MotionGraph> graph,
                      const std::string& ref_error) {
    BatchClipResult& c = summary.clips[i];  // only this worker touches clip i
    const Clock::time_point t0 = Clock::now();
    if (!graph) {
      c.status = "failed";
      c.error = "reference '" + r.clip->stem + "' is unusable: " + ref_error;
      c.output.clear();
      return;
    }
    const ClipFiles& t = tests.at(c.test_stem);
    try {
      SpeechFiles speech;
      speech.audio = t.wav;
      speech.transcript = t.transcript;
      const Reenactment re = reenact(*graph, speech, clip_config, r.clip->bvh);
      bvh_write(c.output, re.motion);
      if (options.reports) {
        const std::string json = re.report.dump(2) + "\n";
        write_file_atomically((out_dir / (c.test_stem + ".json")).string(), [&](std::ostream& os) { os << json; });
      }
      c.frames = re.motion.frame_count;
      const auto totals = re.report.find("totals");
      if (totals != re.report.end()) {
        c.fallbacks = fallback_total(*totals);
        if (totals->contains("failures") && (*totals)["failures"].is_number()) c.failures = (*totals)["failures"].get<int>();
      }
      c.status = "ok";
    } catch (const std::exception& e) {
      c.status = "failed";
      c.error = e.what();
      c.output.clear();
    }
    c.seconds = seconds_since(t0);
  };

  auto worker = [&] {
    std::unique_lock<std::mutex> lock(m);
    for (;;) {
      // Pick: a clip whose graph is ready (or failed), else a graph to build, else wait.
      RefState* ready = nullptr;
      RefState* unbuilt = nullptr;
      if (cancelled() || pending_total == 0) return;
      for (RefState& r : ref_states) {
        if (r.pending.empty()) continue;
        if (r.state == RefState::State::Ready || r.state == RefState::State::Failed) {
          ready = &r;
          break;
        }
        if (r.state == RefState::State::Unbuilt && !unbuilt) unbuilt = &r;
      }
      if (ready) {
        const std::size_t i = ready->pending.front();
        ready->pending.pop_front();
        --pending_total;
        std::shared_ptr<const MotionGraph> graph = ready->graph;
        const std::string ref_error = ready->error;
        lock.unlock();
        run_clip(i, *ready, graph, ref_error);
        graph.reset();
        lock.lock();
        BatchClipResult& c = summary.clips[i];
        ++finished;
        const std::string head = "[" + std::to_string(finished) + "/" + std::to_string(total) + "] " + c.test_stem;
        if (c.status == "ok") {
          const std::string t = fixed(c.seconds, 2) + "s";
          std::string plain = head + " ok " + t + " (reference " + c.reference_stem + ", " + std::to_string(c.frames) +
                              " frames";
          if (c.fallbacks) plain += ", " + std::to_string(c.fallbacks) + " fallbacks";
          if (c.failures) plain += ", " + std::to_string(c.failures) + " failures";
          progress.status(head + " ok " + t, plain + ")");
        } else {
          progress.line(head + " FAILED: " + c.error);
        }
        if (--ready->outstanding == 0) ready->graph.reset();  // the last clip of this reference
        cv.notify_all();
        continue;
      }
      if (unbuilt) {
        unbuilt->state = RefState::State::Building;
        RefState& r = *unbuilt;
        lock.unlock();
        const Clock::time_point t0 = Clock::now();
        std::shared_ptr<const MotionGraph> graph;
        std::string error;
        try {
          ReferenceFiles files;
          files.motion = r.clip->bvh;
          files.speech.audio = r.clip->wav;
          files.speech.transcript = r.clip->transcript;
          graph = std::make_shared<const MotionGraph>(graph_build_from_files({files}, clip_config));
        } catch (const std::exception& e) {
          error = e.what();
        }
        const double secs = seconds_since(t0);
        lock.lock();
        BatchReferenceResult& rr = summary.references[r.result_index];
        rr.build_seconds = secs;
        if (graph) {
          rr.frames = graph->frame_count();
          r.graph = std::move(graph);
          r.state = RefState::State::Ready;
          progress.line("batch: graph of " + r.clip->stem + ": " + std::to_string(rr.frames) + " frames, built in " +
                        fixed(secs, 2) + "s");
        } else {
          rr.error = error;
          r.error = error;
          r.state = RefState::State::Failed;
          progress.line("batch: reference " + r.clip->stem + " FAILED: " + error);
        }
        cv.notify_all();
        continue;
      }
      // Every clip left waits for a graph under construction.
      cv.wait_for(lock, std::chrono::milliseconds(200));
    }
  };

  if (to_do > 0) {
    std::vector<std::thread> threads;
    for (std::size_t w = 1; w < worker_count; ++w) threads.emplace_back(worker);
    worker();
    for (std::thread& t : threads) t.join();
  }
  progress.finish();

  // ---- totals and records ----
  for (BatchClipResult& c : summary.clips) {
    if (c.status.empty()) {
      c.status = "cancelled";
      c.output.clear();
    }
    if (c.status == "ok") ++summary.ok;
    else if (c.status == "failed") ++summary.failed;
    else if (c.status == "skipped") ++summary.skipped;
    else ++summary.cancelled;
  }
  summary.interrupted = cancelled();
  for (const BatchReferenceResult& r : summary.references) summary.graph_seconds += r.build_seconds;
  summary.seconds = seconds_since(t_start);

  write_file_atomically((out_dir / "summary.csv").string(), [&](std::ostream& os) {
    os << csv_line({"test_stem", "reference_stem", "status", "frames", "fallbacks", "failures", "seconds", "output",
                    "error"});
    for (const BatchClipResult& c : summary.clips)
      os << csv_line({c.test_stem, c.reference_stem, c.status, std::to_string(c.frames), std::to_string(c.fallbacks),
                      std::to_string(c.failures), fixed(c.seconds, 3), c.output, c.error});
  });
  const std::string json = summary_json(summary, options, pairing).dump(2) + "\n";
  write_file_atomically((out_dir / "summary.json").string(), [&](std::ostream& os) { os << json; });

  {
    std::ostringstream os;
    os << "batch: " << summary.ok << " ok, " << summary.failed << " failed, " << summary.skipped << " skipped";
    if (summary.cancelled) os << ", " << summary.cancelled << " cancelled (interrupted)";
    os << " in " << fixed(summary.seconds, 1) << "s (graphs " << fixed(summary.graph_seconds, 1)
       << "s); summary in " << (out_dir / "summary.csv").string();
    progress.line(os.str());
  }
  return summary;
}

// ---------------------------------------------------------------------------------------------
// Command line.

namespace {

std::atomic<bool> g_interrupt{false};

void batch_on_signal(int sig) {
  if (g_interrupt.load()) {  // second signal: die the ordinary way
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_interrupt.store(true);
}

// Installs the handler for SIGINT and SIGTERM while alive.
class InterruptGuard {
 public:
  InterruptGuard() {
    g_interrupt.store(false);
    struct sigaction sa {};
    sa.sa_handler = batch_on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    ::sigaction(SIGINT, &sa, &old_int_);
    ::sigaction(SIGTERM, &sa, &old_term_);
  }
  ~InterruptGuard() {
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
  }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

struct BatchCliState {
  BatchOptions options;
  std::string config_file;
  std::vector<std::string> sets;
  std::uint64_t seed = 0;
  std::string progress = "auto";
};

}  // namespace

void add_batch_command(CLI::App& app, int* exit_code) {
  CLI::App* sub = app.add_subcommand(
      "batch",
      "reenact many test clips against a pool of references: one BVH per test clip, named after its stem, "
      "plus pairs.csv, summary.csv and summary.json in OUTDIR");
  auto st = std::make_shared<BatchCliState>();
  BatchOptions& o = st->options;
  sub->add_option("--pool", o.pool_dirs,
                  "folder of reference clips (BVH + WAV + optional .tsv/.TextGrid/.json with matching stems, flat or in "
                  "bvh/ wav/ tsv/ subfolders); repeatable");
  sub->add_option("--pool-manifest", o.pool_manifests, "CSV of reference clips with header stem,bvh,wav,transcript; repeatable");
  sub->add_option("--tests", o.test_dirs, "folder of test clips (WAV + optional transcript, matching stems); repeatable");
  sub->add_option("--test-manifest", o.test_manifests, "CSV of test clips with header stem,wav,transcript; repeatable");
  sub->add_option("-o,--output", o.output_dir, "output folder (created when missing)")->required();
  sub->add_option("--pairing", o.pairing, "random (default) or manifest")
      ->check(CLI::IsMember({"random", "manifest"}));
  sub->add_option("--manifest", o.pairs_manifest, "CSV test_stem,reference_stem (implies --pairing manifest)");
  sub->add_option("--blacklist", o.blacklist, "file of pool stems to leave out, one a line ('#' comments)");
  CLI::Option* seed_opt = sub->add_option("--seed", st->seed, "seed of the pairing draw and of every reenactment");
  sub->add_option("--jobs,-j", o.jobs, "parallel clips (default 0: all cores)")->check(CLI::NonNegativeNumber);
  sub->add_flag("--force", o.force, "redo clips whose output BVH exists");
  sub->add_flag("--reports", o.reports, "also write OUTDIR/<stem>.json, each reenactment's report");
  sub->add_option("--progress", st->progress, "auto (updating line on a terminal), lines, or none")
      ->check(CLI::IsMember({"auto", "lines", "none"}));
  sub->add_option("--config", st->config_file, "JSON config file of engine parameters");
  sub->add_option("--set", st->sets, "engine parameter key=value; repeatable");

  sub->callback([st, seed_opt, exit_code] {
    try {
      const Config config = config_from(st->config_file, st->sets);
      BatchOptions options = st->options;
      if (seed_opt->count() > 0) options.seed = st->seed;
      options.progress = st->progress == "lines"  ? BatchProgress::Lines
                         : st->progress == "none" ? BatchProgress::Quiet
                                                  : BatchProgress::Auto;
      InterruptGuard guard;
      options.cancel = &g_interrupt;
      const BatchSummary s = batch_run(options, config, std::cerr);
      *exit_code = s.interrupted ? 130 : s.failed > 0 ? 1 : 0;
    } catch (const std::exception& e) {
      std::cerr << "gmg: error: " << e.what() << "\n";
      *exit_code = 2;
    }
  });
}

}  // namespace gmg
