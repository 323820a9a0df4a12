#pragma once
/// A run's `--out DIR`: its outputs are written as one set and appear together, or not at all.
/// - Created (with its parents) and locked (folder_lock.hpp) for the run, so a second run into
///   it fails at once rather than mixing its files with this one's.
/// - Every output is written into a staging folder of this run, `DIR/.tumble-run.XXXXXX.partial/`,
///   under its final name there; commit() moves each into DIR in the order they were staged
///   (run.json, the manifest, is staged last, so it lands last), then removes the staging folder.
///   A file replaces the previous one atomically, or is written through into a device or FIFO
///   (output_target.hpp); a folder (frames/) replaces the previous folder as a whole, so it is
///   always one run's frames, never a mix and never a remainder of a longer run.
/// - Destroyed without commit() (an error, a divergence, a full disk, SIGINT/SIGTERM/SIGHUP/
///   SIGQUIT) the staging folder is removed and DIR is exactly as before. Staging folders that a
///   killed run (SIGKILL, a crash) left behind are removed by the next run into DIR.
/// Nothing this run did not write is deleted: a file of an earlier run that this one does not
/// write (another option set) stays, and run.json, listing exactly this run's outputs, says
/// which files are this run's. A folder output that holds files tumble did not write is
/// refused rather than replaced.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "tumble/error.hpp"
#include "tumble/folder_lock.hpp"

namespace tumble {

/// Where an output is written now (`staged`), and the name it will have (`final`).
struct StagedOutput {
  std::filesystem::path final;
  std::filesystem::path staged;
};

class OutputFolder {
 public:
  /// Creates and locks `dir` and makes its staging folder. Throws tumble::Error (Environment).
  explicit OutputFolder(std::filesystem::path dir);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& dir() const { return dir_; }

  /// A file output `DIR/name`. Checked now, before the run does any work: a folder in its place
  /// is an error (Environment). The writer writes `staged` (which does not exist yet).
  StagedOutput file(const std::string& name);
  /// A folder output `DIR/name` of files whose names `is_own` accepts (frames/frame_NNNNN.png).
  /// Checked now: an existing `DIR/name` must be a real folder holding only such files (and
  /// tumble's own `.partial` temporaries). `staged` is created, empty.
  StagedOutput folder(const std::string& name, std::function<bool(const std::string&)> is_own);

  /// The staged file behind a final output path (run.json's digests are taken before commit);
  /// a path outside DIR is returned as it is.
  std::filesystem::path staged_path_of(const std::filesystem::path& final_path) const;

  /// Puts every staged output in place, in the order staged. Throws tumble::Error (Environment).
  void commit();

  /// `e` with the staging folder's paths in its message replaced by their final names, so a
  /// failure names the file the user asked for.
  Error in_final_names(const Error& e) const;

 private:
  struct Entry {
    std::string name;
    bool folder = false;
    std::function<bool(const std::string&)> is_own;
  };
  void check_folder(const Entry& entry) const;
  void place_folder(const Entry& entry) const;

  std::filesystem::path dir_;
  FolderLock lock_;
  std::filesystem::path staging_;
  std::vector<Entry> entries_;
};

}  // namespace tumble
