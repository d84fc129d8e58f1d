// Splitting test speech into subsequences (SPEC "Test speech segmentation").
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace gmg {

enum class Termination {
  Rhythm,   // end at any onset or break node
  Keyword,  // end at a keyword node with the same label
  Frame,    // end at graph frame `stop_frame` (the first frame of a pinned stretch that follows)
};

// What decides a subsequence's frames (search/anchors.h): the planner, or an anchor.
enum class Fixed {
  None,  // planned (the paper's subsequence)
  Rest,  // a still stretch of the reference, chosen by the planner where the new speech pauses
  Pin,   // graph frames [source, source + length), given
};

struct Subsequence {
  int start = 0;   // first test frame
  int length = 0;  // target length l_sub in frames (>= 1)
  Termination kind = Termination::Rhythm;
  std::string keyword;  // the label when kind == Keyword
  int stop_frame = -1;  // the graph frame when kind == Frame
  Fixed fixed = Fixed::None;
  int source = -1;  // Pin: the first graph frame it plays
  int lead = 0;     // Rest: frames before the still part (the reference's own way into its rest)
};

// Boundaries are the sorted unique key frames in (0, total) together with 0 and total. A
// subsequence ends with keyword termination when its end frame is a keyword frame (the first
// keyword listed for that frame wins), otherwise with rhythm; the last one ends at total with
// rhythm. Frames outside (0, total) are ignored. total >= 1.
std::vector<Subsequence> segment_speech(int total, const std::vector<int>& onset_frames,
                                        const std::vector<std::pair<int, std::string>>& keyword_frames);

// The natural planner's merge: a subsequence shorter than `min_length` frames joins the next one
// (which keeps its end and termination); a short last one joins the one before it. Lengths still
// sum to the same total; min_length <= 1 changes nothing.
std::vector<Subsequence> merge_short_subsequences(const std::vector<Subsequence>& subs, int min_length);

}  // namespace gmg
