#pragma once
// The temporary file an encoder writes before its output is complete: beside the final file, so
// the rename into place never crosses file systems, and a dot-name (".clip.mp4.partial"), as
// AtomicFile's, so a half-written clip stays out of globs like *.mp4. Removed when its owner is
// destroyed without having released it (an error, an interrupted run).

#include <filesystem>
#include <string>
#include <system_error>

namespace tumble {

inline std::filesystem::path partial_path_for(const std::filesystem::path& final_path) {
  // Built by appending: GCC 12 misreports `"." + string` as an overlapping memcpy (-Wrestrict).
  std::string name = ".";
  name.append(final_path.filename().string());
  name.append(".partial");
  return final_path.parent_path() / name;
}

/// Removes a file when destroyed, unless released: the half-written output of a writer that
/// never reached finish().
class RemoveUnlessReleased {
 public:
  explicit RemoveUnlessReleased(std::filesystem::path path) : path_(std::move(path)) {}
  ~RemoveUnlessReleased() {
    if (path_.empty()) return;
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  RemoveUnlessReleased(const RemoveUnlessReleased&) = delete;
  RemoveUnlessReleased& operator=(const RemoveUnlessReleased&) = delete;
  void release() { path_.clear(); }

 private:
  std::filesystem::path path_;
};

/// Renames the finished temporary file into place; throws tumble::Error (Environment) naming the
/// final path when it cannot.
void rename_into_place(const std::filesystem::path& temporary, const std::filesystem::path& final);

}  // namespace tumble
