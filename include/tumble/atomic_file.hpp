#pragma once
/// An output file that appears under its final name only when complete: bytes go to a
/// temporary file beside it (same folder, so the rename is atomic), which commit() renames into
/// place. Destroyed without commit() — an error, an exception — the temporary is removed and a
/// previous good file under the final name is left untouched.

#include <filesystem>
#include <fstream>
#include <string_view>

namespace tumble {

class AtomicFile {
 public:
  /// Opens the temporary file. Throws tumble::Error (Environment) when it cannot.
  explicit AtomicFile(std::filesystem::path final_path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  void write(std::string_view bytes) { out_.write(bytes.data(), static_cast<long>(bytes.size())); }
  /// Flushes, closes and renames into place. Throws tumble::Error (Environment) on failure.
  void commit();

  const std::filesystem::path& path() const { return final_; }
  const std::filesystem::path& temporary_path() const { return temporary_; }

 private:
  std::filesystem::path final_, temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Writes `bytes` to `path` atomically (see AtomicFile).
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// Creates `dir` and its parents. Throws tumble::Error (Environment) when it cannot.
void make_output_dir(const std::filesystem::path& dir);

}  // namespace tumble
