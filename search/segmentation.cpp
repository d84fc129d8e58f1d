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

}  // namespace gmg
