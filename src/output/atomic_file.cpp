#include "tumble/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>

#include "cannot_write.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

// A regular target is staged beside what it names, so that the rename never crosses file
// systems; a device or FIFO gets its bytes by copying, so the temporary folder serves (the
// device's own folder, /dev, is no place for files and often not writable).
fs::path staging_folder(const OutputTarget& t) {
  if (t.kind == OutputTarget::Kind::WriteThrough) return fs::temp_directory_path();
  return t.resolved.has_parent_path() ? t.resolved.parent_path() : fs::path(".");
}

}  // namespace

StagedFile::StagedFile(fs::path final_path)
    : target_(output_target(final_path)),
      temporary_(make_unique_temporary_file(staging_folder(target_),
                                            target_.resolved.filename().string())) {}

StagedFile::~StagedFile() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

void StagedFile::commit() {
  place_output(temporary_, target_);
  committed_ = true;
}

AtomicFile::AtomicFile(fs::path final_path) : staged_(std::move(final_path)) {
  out_.open(staged_.temporary_path(), std::ios::binary | std::ios::trunc);
  if (!out_) cannot_write(staged_.path(), std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  out_.close();
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail()) cannot_write(staged_.path(), "write failed (disk full?)");
  staged_.commit();
}

void write_file_atomically(const fs::path& path, std::string_view bytes) {
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
}

void make_output_dir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error(ErrorKind::Environment, "cannot create output folder \"" + dir.string() + "\": " +
                                            (ec ? ec.message() : std::string("not a folder")));
}

}  // namespace tumble
