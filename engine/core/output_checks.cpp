#include "engine/core/output_checks.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <sys/stat.h>
#include <unistd.h>

#include "engine/core/error.h"
#include "engine/core/file_read.h"
#include "engine/core/strings.h"

namespace gmg {
namespace fs = std::filesystem;

namespace {

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  // Not both there yet: the same name after resolving the folders that exist.
  const fs::path ca = fs::weakly_canonical(a, ec);
  if (ec) return false;
  const fs::path cb = fs::weakly_canonical(b, ec);
  return !ec && ca == cb;
}

}  // namespace

void check_outputs_apart(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedFile& out = outputs[i];
    if (out.path.empty()) continue;
    for (const NamedFile& in : inputs) {
      if (in.path.empty() || !same_file(out.path, in.path)) continue;
      throw Error(out.path + ": " + out.option + " would overwrite the input given as " + in.option +
                  (in.path == out.path ? "" : " (" + in.path + ")") + "; choose another output");
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (outputs[k].path.empty() || !same_file(out.path, outputs[k].path)) continue;
      throw Error(out.path + ": given as both " + outputs[k].option + " and " + out.option +
                  "; each output needs its own file");
    }
  }
}

namespace {

std::string option_text(const NamedFile& f) { return f.option.empty() ? std::string() : f.option + " "; }

// The reason a folder cannot take new files ("Permission denied", "Read-only file system"), or
// "" when it can. access(2) also sees a read-only mount, which the permission bits do not show.
std::string unwritable_reason(const fs::path& dir) {
  if (::access(dir.empty() ? "." : dir.c_str(), W_OK | X_OK) == 0) return "";
  return std::strerror(errno);
}

}  // namespace

std::string extension_list(const std::vector<std::string>& extensions) {
  std::string out;
  for (std::size_t i = 0; i < extensions.size(); ++i) {
    if (i > 0) out += i + 1 == extensions.size() ? " or " : ", ";
    out += extensions[i];
  }
  return out;
}

void check_output_file(const NamedFile& output, const std::vector<std::string>& extensions) {
  const std::string& path = output.path;
  if (path.empty()) return;
  const std::string opt = option_text(output);
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(path + ": " + opt + "is a folder, not a file");
    if (!S_ISREG(st.st_mode)) throw Error(path + ": " + opt + "is " + file_kind(st.st_mode) + ", not a regular file");
  }
  if (!extensions.empty() &&
      std::none_of(extensions.begin(), extensions.end(), [&](const std::string& e) { return ends_with_ci(path, e); }))
    throw Error(path + ": " + opt + "must be a " + extension_list(extensions) +
                " file (its extension chooses the format)");
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw Error(path + ": " + (opt.empty() ? "" : output.option + ": ") + "the folder " + parent.string() +
                " does not exist");
  const std::string reason = unwritable_reason(parent);
  if (!reason.empty())
    throw Error(path + ": " + (opt.empty() ? "" : output.option + ": ") + "cannot write into the folder " +
                (parent.empty() ? std::string(".") : parent.string()) + " (" + reason + ")");
}

void check_output_folder(const NamedFile& output) {
  const std::string& path = output.path;
  if (path.empty()) return;
  const std::string opt = option_text(output);
  std::error_code ec;
  fs::path dir(path);
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
    throw Error(path + ": " + opt + "is " + (S_ISREG(st.st_mode) ? "a file" : file_kind(st.st_mode)) +
                ", not a folder");
  // The folder itself when it exists, else the nearest one above it (where it will be created).
  while (!dir.empty() && !fs::exists(dir, ec)) dir = dir.parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw Error(path + ": " + (opt.empty() ? "" : output.option + ": ") + dir.string() + " is a file, not a folder");
  const std::string reason = unwritable_reason(dir);
  if (!reason.empty())
    throw Error(path + ": " + (opt.empty() ? "" : output.option + ": ") + "cannot write into the folder " +
                (dir.empty() ? std::string(".") : dir.string()) + " (" + reason + ")");
}

}  // namespace gmg
