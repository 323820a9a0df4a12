#pragma once
/// An output that appears under its final name only when complete. The one way tumble opens,
/// stages and commits an output file (every command, every sink, the video writers):
/// - StagedFile: checks the target (output_target.hpp: a regular file or nothing is replaced, a
///   device or FIFO is written through, a missing parent folder is an error) and makes a
///   temporary file with a name unique to this process (`.<name>.XXXXXX.partial`, beside the
///   target so the rename is atomic; in the system's temporary folder for a device or FIFO).
///   A writer writes there; commit() puts it in place. Destroyed without commit() — an error,
///   an exception, an interrupted run — the temporary is removed and whatever the final name
///   held is left untouched.
/// - AtomicFile: a StagedFile with a stream to write into.

#include <filesystem>
#include <fstream>
#include <string_view>

#include "tumble/output_target.hpp"

namespace tumble {

class StagedFile {
 public:
  /// Checks the target and makes the (empty) temporary file. Throws tumble::Error
  /// (Environment) when the target cannot take a file or the temporary cannot be made.
  explicit StagedFile(std::filesystem::path final_path);
  ~StagedFile();
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  /// Renames the temporary into place, or writes it through (output_target.hpp). Throws
  /// tumble::Error (Environment); the temporary is then still removed on destruction.
  void commit();

  const std::filesystem::path& path() const { return target_.path; }
  /// Where the writer writes (a regular file, created empty).
  const std::filesystem::path& temporary_path() const { return temporary_; }

 private:
  OutputTarget target_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

class AtomicFile {
 public:
  /// Opens the temporary file. Throws tumble::Error (Environment) when it cannot.
  explicit AtomicFile(std::filesystem::path final_path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  void write(std::string_view bytes) { out_.write(bytes.data(), static_cast<long>(bytes.size())); }
  /// Flushes, closes and puts the file in place. Throws tumble::Error (Environment) on failure.
  void commit();

  const std::filesystem::path& path() const { return staged_.path(); }
  const std::filesystem::path& temporary_path() const { return staged_.temporary_path(); }

 private:
  StagedFile staged_;  // declared first: the stream is closed before the temporary goes
  std::ofstream out_;
};

/// Writes `bytes` to `path` atomically (see AtomicFile).
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// Creates `dir` and its parents (an `--out` folder). Throws tumble::Error (Environment) when
/// it cannot.
void make_output_dir(const std::filesystem::path& dir);

}  // namespace tumble
