// The clips of clip folders and manifests (batch.h, "Inputs"): how `gmg batch` finds its pool
// and test clips, and how `gmg build --clips` finds the clips of one graph.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "engine/batch/batch.h"

namespace gmg::batch {

struct ClipFiles {
  std::string stem, bvh, wav, transcript;  // bvh is empty for a test clip; wav is the audio in any format
  std::string origin;                      // folder or "manifest:line", for messages
  std::string error{};                     // why the clip cannot be made (a broken link, no audio); "" = fine
};

using ClipMap = std::map<std::string, ClipFiles>;  // by stem

struct Clips {
  ClipMap pool, tests;
  std::vector<std::string> notes;  // files found but not used (a BVH without WAV in a pool), broken links
};

// The reference clips (BVH + WAV + optional transcript) of clip folders and manifests, as a batch
// pool reads them (see batch.h); files found but not used are described in `notes`. Also what
// `gmg build --clips` reads.
ClipMap collect_reference_clips(const std::vector<std::string>& dirs, const std::vector<std::string>& manifests,
                                std::vector<std::string>& notes);

// Every pool and test clip of the options' folders and manifests (see batch.h). Throws
// gmg::Error on a setup problem: an unreadable folder or manifest, a stem given twice, no pool
// or no test clip at all.
Clips collect_clips(const BatchOptions& options);

}  // namespace gmg::batch
