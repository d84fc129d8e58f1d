#include "search/segmentation.h"

#include <algorithm>
#include <map>

#include "engine/core/error.h"

namespace gmg {

std::vector<Subsequence> segment_speech(int total, const std::vector<int>& onset_frames,
                                        const std::vector<std::pair<int, std::string>>& keyword_frames) {
  if (total < 1) throw Error("segment_speech: the test speech is shorter than one frame");
  std::map<int, std::string> keyword_at;
  for (const auto& [frame, word] : keyword_frames)
    if (frame > 0 && frame < total) keyword_at.emplace(frame, word);  // emplace keeps the first
  std::vector<int> bounds = {0, total};
  for (int f : onset_frames)
    if (f > 0 && f < total) bounds.push_back(f);
  for (const auto& entry : keyword_at) bounds.push_back(entry.first);
  std::sort(bounds.begin(), bounds.end());
  bounds.erase(std::unique(bounds.begin(), bounds.end()), bounds.end());

  std::vector<Subsequence> out;
  for (std::size_t i = 0; i + 1 < bounds.size(); ++i) {
    Subsequence s;
    s.start = bounds[i];
    s.length = bounds[i + 1] - bounds[i];
    const auto it = keyword_at.find(bounds[i + 1]);
    if (it != keyword_at.end()) {
      s.kind = Termination::Keyword;
      s.keyword = it->second;
    }
    out.push_back(s);
  }
  return out;
}

std::vector<Subsequence> merge_short_subsequences(const std::vector<Subsequence>& subs, int min_length) {
  std::vector<Subsequence> out;
  int pending_start = -1;  // start of short subsequences waiting to join the next
  for (const Subsequence& s : subs) {
    Subsequence merged = s;
    if (pending_start >= 0) {
      merged.length += merged.start - pending_start;
      merged.start = pending_start;
      pending_start = -1;
    }
    if (merged.length < min_length) {
      pending_start = merged.start;
      continue;
    }
    out.push_back(merged);
  }
  if (pending_start >= 0) {
    const int end = subs.back().start + subs.back().length;
    if (out.empty()) {
      Subsequence all = subs.back();
      all.start = pending_start;
      all.length = end - pending_start;
      out.push_back(all);
    } else {
      // The short tail joins the last kept piece, which now ends where the speech ends.
      Subsequence& last = out.back();
      last.length = end - last.start;
      last.kind = subs.back().kind;
      last.keyword = subs.back().keyword;
    }
  }
  return out;
}

}  // namespace gmg
