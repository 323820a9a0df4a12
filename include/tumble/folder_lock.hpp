#pragma once
/// One run at a time per output folder: an exclusive flock(2) on `DIR/.tumble.lock`, held for
/// the run. A second run that finds it held fails at once (tumble::Error, Environment, naming the
/// folder and saying another run is writing it) instead of mixing its outputs with the first's.
/// The kernel drops the lock when its holder dies, however it dies, so a crashed run never
/// blocks the next one; a run that ends normally also removes the file.

#include <filesystem>

namespace tumble {

class FolderLock {
 public:
  /// Takes the lock of the folder `dir` (which exists). Throws tumble::Error (Environment).
  explicit FolderLock(const std::filesystem::path& dir);
  /// Removes the lock file, then releases the lock.
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  /// The lock file's name in the folder.
  static constexpr const char* kFileName = ".tumble.lock";

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace tumble
