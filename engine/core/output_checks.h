// Checking outputs before any work: that each can be written as the file or folder it names, and
// that none is an input or another output, so a job never does its work for an output it cannot
// write, nor writes over what it reads.
#pragma once

#include <string>
#include <vector>

namespace gmg {

// A file named on the command line, with the option that named it ("-o", "--audio").
struct NamedFile {
  std::string option;
  std::string path;
};

// Throws gmg::Error before any work when `output` cannot be written as the file it names, so a
// job never does its work for an output it cannot write (the option is left out of the message
// when empty; each check names the file first, then the cause):
//   "out.txt: -o must be a .bvh or .npz file (its extension chooses the format)"  (extensions:
//       ASCII case-insensitive, with the dot; empty = any)
//   "out: -o is a folder, not a file"   (also a FIFO, a device, a socket: "is a FIFO (named pipe)")
//   "a/b/out.bvh: -o: the folder a/b does not exist"
//   "ro/out.bvh: -o: cannot write into the folder ro (Read-only file system)"
void check_output_file(const NamedFile& output, const std::vector<std::string>& extensions);

// The same for an output folder (created when missing): "out: -o is a file, not a folder", and
// the folder, or the nearest one above it that exists, must be writable.
void check_output_folder(const NamedFile& output);

// " or ": ".bvh or .npz", ".mp4, .mkv or .mov".
std::string extension_list(const std::vector<std::string>& extensions);

// Throws gmg::Error before any work when an output is an input (the same file, also through a
// symbolic or hard link: compared with std::filesystem::equivalent) or two outputs are the same
// file: "in.bvh: -o would overwrite the input given as --motion; choose another output". Empty
// paths are ignored.
void check_outputs_apart(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs);

}  // namespace gmg
