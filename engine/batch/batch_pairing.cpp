// Pairing test clips with references: the seeded draw, the blacklist, the pairs manifest, and
// the record of the pairing (OUTDIR/pairs.csv).
#include <algorithm>
#include <random>

#include "engine/batch/batch_internal.h"
#include "engine/core/csv.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"

namespace gmg {

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

namespace batch {
namespace {

// A blacklist line may be a file name or path: its folder and a clip extension are dropped.
std::string stem_of_listed(std::string s) {
  const std::size_t slash = s.find_last_of("/\\");
  if (slash != std::string::npos) s = s.substr(slash + 1);
  const std::size_t dot = s.find_last_of('.');
  if (dot != std::string::npos) {
    const std::string ext = ascii_lower(s.substr(dot));
    if (ext == ".bvh" || ext == ".wav" || ext == ".tsv" || ext == ".textgrid" || ext == ".json") s.resize(dot);
  }
  return s;
}

bool is_pairs_header(const CsvRow& row) {
  if (row.fields.size() < 2) return false;
  const std::string a = ascii_lower(row.fields[0]), b = ascii_lower(row.fields[1]);
  return (a == "test_stem" || a == "test") && (b == "reference_stem" || b == "reference");
}

Pairing draw_pairing(const std::vector<std::string>& test_stems, const std::vector<std::string>& pool_stems,
                     std::uint64_t seed) {
  Pairing p;
  p.test_stems = test_stems;
  p.references = batch_draw_references(test_stems, pool_stems, seed);
  p.errors.resize(test_stems.size());
  for (std::size_t i = 0; i < p.references.size(); ++i)
    if (p.references[i].empty()) p.errors[i] = "no reference clip to draw from (the pool holds only this clip)";
  return p;
}

Pairing manifest_pairing(const std::vector<std::string>& test_stems, const std::string& manifest, const Clips& clips,
                         const std::set<std::string>& blacklist) {
  const std::map<std::string, std::string> pairs = read_pairs(manifest, true);
  for (const auto& [t, r] : pairs)
    if (!clips.tests.count(t)) {
      std::string message = manifest;
      message += ": test clip '" + t + "' is not among the test clips";
      throw Error(message);
    }
  Pairing p;
  p.test_stems = test_stems;
  p.references.resize(test_stems.size());
  p.errors.resize(test_stems.size());
  for (std::size_t i = 0; i < test_stems.size(); ++i) {
    const auto it = pairs.find(test_stems[i]);
    if (it == pairs.end()) {
      p.errors[i] = "not paired in " + manifest;
      continue;
    }
    p.references[i] = it->second;
    if (blacklist.count(it->second))
      p.errors[i] = "reference '" + it->second + "' (from " + manifest + ") is blacklisted";
    else if (!clips.pool.count(it->second))
      p.errors[i] = "reference '" + it->second + "' (from " + manifest + ") is not in the pool";
  }
  return p;
}

}  // namespace

std::set<std::string> read_blacklist(const std::string& path) {
  std::set<std::string> out;
  for (const std::string& text : split_lines(read_file_bytes(path))) {
    std::string_view line = text;
    line = line.substr(0, line.find('#'));
    line = trim(line);
    if (has_utf8_bom(line)) line = trim(line.substr(3));
    if (!line.empty()) out.insert(stem_of_listed(std::string(line)));
  }
  return out;
}

std::map<std::string, std::string> read_pairs(const std::string& path, bool strict) {
  std::map<std::string, std::string> out;
  const std::vector<CsvRow> rows = csv_read_file(path);
  const std::size_t first = !rows.empty() && is_pairs_header(rows[0]) ? 1 : 0;
  for (std::size_t r = first; r < rows.size(); ++r) {
    const CsvRow& row = rows[r];
    if (row.fields.size() < 2 || row.fields[0].empty() || row.fields[1].empty()) {
      if (strict) throw Error(error_at_line(path, row.line, "expected 'test_stem,reference_stem'"));
      continue;
    }
    auto [it, inserted] = out.emplace(row.fields[0], row.fields[1]);
    if (!inserted && it->second != row.fields[1]) {
      if (strict)
        throw Error(error_at_line(
            path, row.line,
            "test clip '" + row.fields[0] + "' is paired twice ('" + it->second + "' and '" + row.fields[1] + "')"));
      it->second = row.fields[1];
    }
  }
  return out;
}

Pairing pair_tests(const BatchOptions& options, BatchPairing mode, const Clips& clips,
                   const std::set<std::string>& blacklist, const std::vector<std::string>& pool_stems,
                   std::uint64_t seed) {
  std::vector<std::string> test_stems;
  for (const auto& [stem, c] : clips.tests) test_stems.push_back(stem);
  if (mode == BatchPairing::Random) return draw_pairing(test_stems, pool_stems, seed);
  return manifest_pairing(test_stems, options.pairs_manifest, clips, blacklist);
}

std::map<std::string, std::string> read_previous_pairs(const fs::path& out_dir) {
  std::error_code ec;
  const fs::path prev = out_dir / "pairs.csv";
  if (!fs::exists(prev, ec)) return {};
  try {
    return read_pairs(prev.string(), false);
  } catch (const std::exception&) {
    return {};  // an unreadable old record is only lost information
  }
}

void write_pairs_csv(const fs::path& out_dir, const std::vector<BatchClipResult>& clips) {
  write_file_atomically((out_dir / "pairs.csv").string(), [&](std::ostream& os) {
    os << csv_line({"test_stem", "reference_stem"});
    for (const BatchClipResult& c : clips)
      if (!c.reference_stem.empty()) os << csv_line({c.test_stem, c.reference_stem});
  });
}

}  // namespace batch
}  // namespace gmg
