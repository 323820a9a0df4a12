#pragma once
// The text of the diff report's index.html: summary, sections, the in-place compare's style
// and script (inline: the page fetches nothing). Private to the imaging layer: DiffReport
// (diff_report.cpp) decides what is shown and writes the pictures, this only writes the page.

#include <optional>
#include <string>
#include <vector>

#include "tumble/diff_pair.hpp"

namespace tumble::report {

// A picture in the report folder; `src` relative to index.html.
struct Picture {
  std::string src;
  int width = 0, height = 0;
};

// One section of the page: one pair, or a run of consecutive frames only one video has.
struct Section {
  std::vector<std::size_t> pairs;  // indices into the pair list
  // The pictures shown. A pair within tolerance whose pictures are identical has `expected`
  // alone; a one-sided pair the one it has (or none); a frame range none.
  std::optional<Picture> expected, actual, diff;
  bool identical = false;
  bool beyond = false;
};

// The whole page. `sections` are in the order shown (failures first); `frames_limit` is how
// many compared frames of a video are shown at most.
std::string page_html(const DiffInputs& inputs, const std::vector<DiffPair>& pairs,
                      const std::vector<Section>& sections, int frames_limit);

}  // namespace tumble::report
