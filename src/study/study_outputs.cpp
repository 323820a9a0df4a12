// The three study outputs, each written under a temporary name and renamed into place.
#include "tumble/atomic_file.hpp"
#include "tumble/study.hpp"

namespace tumble::study {

std::vector<std::filesystem::path> write_study(const std::filesystem::path& dir,
                                               const StudyResult& result) {
  // Everything is rendered before anything is written: a failure leaves no new file at all.
  const std::string csv = study_csv(result), md = study_markdown(result), svg = study_svg(result);
  const std::vector<std::filesystem::path> paths = {dir / "study.csv", dir / "study.md",
                                                    dir / "study.svg"};
  write_file_atomically(paths[0], csv);
  write_file_atomically(paths[1], md);
  write_file_atomically(paths[2], svg);
  return paths;
}

}  // namespace tumble::study
