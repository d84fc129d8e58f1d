// The zip layer of .npz archives: libzip reading an archive held in memory and writing one.
#include "engine/motion/zip.h"

#include <zip.h>

#include <cstdint>
#include <memory>

#include "engine/core/error.h"
#include "engine/core/limits.h"

namespace gmg {

struct ZipReader::Handle {
  zip_t* zip = nullptr;
  ~Handle() {
    if (zip) zip_discard(zip);
  }
};

ZipReader::ZipReader(const std::string& bytes, const std::string& name)
    : zip_(std::make_unique<Handle>()), name_(name), archive_size_(bytes.size()) {
  // libzip opens zero bytes as an archive without members; as an .npz it is a truncated file.
  if (bytes.empty()) throw Error(name + ": not a readable zip archive, as an .npz must be (the file is empty)");
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  if (source) zip_->zip = zip_open_from_source(source, ZIP_RDONLY | ZIP_CHECKCONS, &error);
  if (!zip_->zip) {
    const std::string why = zip_error_strerror(&error);
    zip_error_fini(&error);
    zip_source_free(source);
    throw Error(name + ": not a readable zip archive, as an .npz must be (" + why + ")");
  }
  zip_error_fini(&error);
  const zip_int64_t n = zip_get_num_entries(zip_->zip, 0);
  for (zip_int64_t i = 0; i < n; ++i) {
    const char* member = zip_get_name(zip_->zip, static_cast<zip_uint64_t>(i), 0);
    names_.emplace_back(member ? member : "");
  }
}

ZipReader::~ZipReader() = default;

bool ZipReader::has(const std::string& member) const { return zip_name_locate(zip_->zip, member.c_str(), 0) >= 0; }

std::string ZipReader::read(const std::string& member) const {
  const std::string where = name_ + ": " + member;
  const zip_int64_t index = zip_name_locate(zip_->zip, member.c_str(), 0);
  if (index < 0) throw Error(where + ": not in the archive");
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat_index(zip_->zip, static_cast<zip_uint64_t>(index), 0, &st) != 0 ||
      (st.valid & (ZIP_STAT_SIZE | ZIP_STAT_COMP_SIZE | ZIP_STAT_COMP_METHOD)) !=
          (ZIP_STAT_SIZE | ZIP_STAT_COMP_SIZE | ZIP_STAT_COMP_METHOD))
    throw Error(where + ": cannot read the member's sizes (" + zip_strerror(zip_->zip) + ")");
  if ((st.valid & ZIP_STAT_ENCRYPTION_METHOD) && st.encryption_method != ZIP_EM_NONE)
    throw Error(where + ": the member is encrypted");
  if (!zip_compression_method_supported(st.comp_method, 0))
    throw Error(where + ": compression method " + std::to_string(st.comp_method) + " is not supported");
  // Before allocating: the declared size must be one the archive can hold (deflate expands at
  // most about 1032:1), so a crafted header cannot ask for gigabytes.
  const bool stored = st.comp_method == ZIP_CM_STORE;
  if (st.comp_size > archive_size_ || (stored ? st.size != st.comp_size : st.size / 1100 > st.comp_size + 1) ||
      st.size > limits::kMaxNpyBytes)
    throw Error(where + ": declares " + std::to_string(st.size) + " bytes from " + std::to_string(st.comp_size) +
                " in an archive of " + std::to_string(archive_size_) + " (corrupt or too large)");
  zip_file_t* file = zip_fopen_index(zip_->zip, static_cast<zip_uint64_t>(index), 0);
  if (!file) throw Error(where + ": cannot open the member (" + zip_strerror(zip_->zip) + ")");
  std::string out(static_cast<std::size_t>(st.size), '\0');
  std::uint64_t got = 0;
  zip_int64_t r = 0;
  while (got < st.size && (r = zip_fread(file, &out[got], st.size - got)) > 0) got += static_cast<std::uint64_t>(r);
  char extra = 0;
  // One more read reaches the end of the member, where libzip checks the CRC.
  if (r >= 0 && got == st.size) r = zip_fread(file, &extra, 1);
  const std::string why = r < 0 ? zip_file_strerror(file) : "";
  zip_fclose(file);
  if (r < 0) throw Error(where + ": corrupt member (" + why + ")");
  if (got != st.size || r != 0)
    throw Error(where + ": the member's data does not have its declared size " + std::to_string(st.size));
  return out;
}

std::string zip_format(const std::vector<ZipMember>& members, const std::string& name) {
  zip_error_t error;
  zip_error_init(&error);
  auto fail = [&](const std::string& why) -> Error {
    zip_error_fini(&error);
    return Error(name + ": cannot make the zip archive (" + why + ")");
  };
  zip_source_t* buffer = zip_source_buffer_create(nullptr, 0, 0, &error);
  if (!buffer) throw fail(zip_error_strerror(&error));
  zip_t* za = zip_open_from_source(buffer, ZIP_TRUNCATE, &error);
  if (!za) {
    zip_source_free(buffer);
    throw fail(zip_error_strerror(&error));
  }
  zip_source_keep(buffer);  // the archive's bytes are read from it after zip_close
  for (const ZipMember& m : members) {
    zip_source_t* s = zip_source_buffer(za, m.bytes.data(), m.bytes.size(), 0);
    const zip_int64_t index = s ? zip_file_add(za, m.name.c_str(), s, ZIP_FL_ENC_UTF_8) : -1;
    if (index < 0) {
      if (s) zip_source_free(s);
      const std::string why = zip_strerror(za);
      zip_discard(za);
      zip_source_free(buffer);
      throw fail(why);
    }
    const auto i = static_cast<zip_uint64_t>(index);
    zip_set_file_compression(za, i, m.deflate ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 0);
    zip_file_set_dostime(za, i, 0, (0 << 9) | (1 << 5) | 1, 0);  // 1980-01-01 00:00
  }
  if (zip_close(za) != 0) {
    const std::string why = zip_strerror(za);
    zip_discard(za);
    zip_source_free(buffer);
    throw fail(why);
  }
  zip_stat_t st;
  zip_stat_init(&st);
  std::string out;
  if (zip_source_stat(buffer, &st) != 0 || zip_source_open(buffer) != 0) {
    const std::string why = zip_error_strerror(zip_source_error(buffer));
    zip_source_free(buffer);
    throw fail(why);
  }
  out.resize(static_cast<std::size_t>(st.size));
  const zip_int64_t r = out.empty() ? 0 : zip_source_read(buffer, &out[0], st.size);
  zip_source_close(buffer);
  zip_source_free(buffer);
  if (r < 0 || static_cast<std::uint64_t>(r) != st.size) throw fail("short read of the archive in memory");
  zip_error_fini(&error);
  return out;
}

}  // namespace gmg
