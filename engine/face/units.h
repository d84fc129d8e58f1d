// The new speech cut into the units the face track plays one reference stretch for (engine/face/
// face_track.h): its phones, and the silences between them, when it has phones; else, and for long
// pauses, windows of a fixed length matched by their sound.
#pragma once

#include <string>
#include <vector>

#include "engine/face/params.h"
#include "text/phones.h"

namespace gmg {

struct FaceUnit {
  double start = 0.0, end = 0.0;  // output frame times (frame f at time f), end > start
  bool phone = false;             // a phone or a short silence between phones; false: a window
  std::string symbol;             // the phone's symbol, "" for a silence (phones only)
  std::string left, right;        // the neighbouring phones' symbols ("" silence or a window)
};

// Units covering frames [0, frames) of a grid of `fps`, in order, each starting where the one before
// ends. From phones (seconds, sorted by start; null or empty for none): each phone a unit (cut where
// it overlaps the one before), each pause between phones a silence unit when at most
// silence_unit_max_s long, else windows; a gap shorter than a frame joins the unit before it.
// Without phones: windows of unit_frames frames (the last one up to half as long again).
std::vector<FaceUnit> face_units(const std::vector<text::Phone>* phones, double fps, int frames,
                                 const FaceParams& params);

}  // namespace gmg
