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

// Whole file as bytes. Throws gmg::Error "path: cannot open file (reason)" when unreadable.
std::string read_file_bytes(const std::string& path);

}  // namespace gmg
