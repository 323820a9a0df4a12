#pragma once
// What `tumble diff` writes besides its stdout lines and diff pictures: the HTML report
// (--report DIR) and the JUnit XML (--junit FILE). The comparison hands every pair here as it
// goes; both are written at the end, whatever the verdict, and neither changes the exit code.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "progress.hpp"
#include "tumble/diff_pair.hpp"
#include "tumble/diff_report.hpp"
#include "tumble/image.hpp"

namespace tumble::cli {

/// `a` and `b` name the same file or folder (false when either does not exist).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

class DiffOutputs {
 public:
  /// Checks --report and --junit before anything is compared (tumble::Error, BadInput: a
  /// folder for --junit, a path that is an input) and starts the report's temporary folder.
  DiffOutputs(const DiffOptions& o, DiffInputs inputs);

  /// A compared pair. `summary` is its stdout line after "NAME: "; `frame` is the frame index
  /// of a video pair (-1 otherwise) and `time_s` its presentation time.
  void compared(const std::string& name, const DiffResult& result, bool beyond,
                const std::string& summary, const Image& expected, const Image& actual,
                long frame = -1, std::optional<double> time_s = {});
  /// A file only one folder has; `present` is that file (shown in the report when it decodes).
  void one_sided(const std::string& name, const std::string& summary, DiffPair::Side side,
                 const std::filesystem::path& present);
  /// `count` frames from `first_frame` that only one video has.
  void one_sided_frames(long first_frame, long count, const std::string& summary,
                        DiffPair::Side side);

  /// Writes the report and the JUnit file. Throws tumble::Error (Environment) when it cannot.
  void finish();

 private:
  void add(DiffPair pair, const Image* expected, const Image* actual);

  DiffInputs inputs_;
  std::unique_ptr<DiffReport> report_;
  std::string junit_;
  std::vector<DiffPair> pairs_;  // for the JUnit file
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_ = start_;  // when the previous pair was done
};

}  // namespace tumble::cli
