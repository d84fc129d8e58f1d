// File helpers shared by every writer: output appears complete or not at all.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace gmg {

// Calls write(stream) on a temporary file beside `path`, then renames it to `path`. When write
// throws or the stream fails, the temporary file is removed, `path` is left untouched and
// gmg::Error (naming `path`) is thrown. So an interrupted or failed job leaves no partial file.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           bool binary = false);

// Whole file as bytes: the one file reader of the engine (WAV, BVH, transcripts, lexicons, JSON
// all come through it), so every "cannot read" error has one wording, "path: what":
//   "x.wav: cannot open (No such file or directory)"
//   "x: is a folder, not a file"
//   "x: read error (Input/output error)"
std::string read_file_bytes(const std::string& path);

}  // namespace gmg
