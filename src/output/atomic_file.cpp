#include "tumble/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>

#include "tumble/error.hpp"

namespace tumble {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& why) {
  throw Error(ErrorKind::Environment, "cannot write \"" + path.string() + "\": " + why);
}

std::string partial_name(const std::filesystem::path& final_path) {
  std::string name = ".";
  name.append(final_path.filename().string());
  name.append(".partial");
  return name;
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path final_path)
    : final_(std::move(final_path)),
      // Beside the final file, so rename() never crosses file systems; a dot-name keeps a
      // half-written file out of globs like frames/*.png.
      temporary_(final_.parent_path() / partial_name(final_)) {
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) fail(final_, std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail()) fail(final_, "write failed (disk full?)");
  std::error_code ec;
  std::filesystem::rename(temporary_, final_, ec);
  if (ec) fail(final_, ec.message());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
}

void make_output_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw Error(ErrorKind::Environment, "cannot create output folder \"" + dir.string() + "\": " +
                                            (ec ? ec.message() : std::string("not a folder")));
}

}  // namespace tumble
