#pragma once
/// `tumble diff --report DIR`: a self-contained HTML report of a comparison, for a person to
/// open from a CI job's artifacts. DIR holds index.html and the PNGs it shows (images/), and
/// nothing else: no script, style sheet or font is fetched, so it works opened from disk and
/// offline. The page has a summary line (pairs, failed, worst delta), then one section per pair,
/// failures first: the verdict, the metrics beside the tolerances, and the expected, actual and
/// diff pictures with an in-place compare (a swipe slider and an expected/actual toggle, both
/// usable with the keyboard). A pair within tolerance whose pictures are identical shows the
/// picture once. For videos only the frames that differ most are shown (kMaxFramesShown), each
/// with its index and time; frames only one video has form one section.
///
/// The folder is built under a temporary name beside DIR and renamed into place by commit(), so
/// DIR is never half-written; a report destroyed without commit() leaves DIR as it was. The same
/// inputs give the same bytes (no time stamps, no absolute paths that were not given).

#include <filesystem>
#include <memory>

#include "tumble/diff_pair.hpp"
#include "tumble/image.hpp"

namespace tumble {

class DiffReport {
 public:
  /// At most this many frames of a video get a section: the ones beyond tolerance first, then
  /// by differing pixels, largest delta and PSNR. Eight keep a report of a long clip small
  /// (24 PNGs) while showing whether a failure is one frame or a stretch; the section list
  /// names every failing frame anyway.
  static constexpr int kMaxFramesShown = 8;

  /// Checks `dir` and creates the temporary folder beside it. Throws tumble::Error: BadInput
  /// when `dir` is a file, is or holds one of the inputs, or is a folder that holds anything
  /// but an earlier report (replacing it would delete files the report did not write);
  /// Environment when the temporary folder cannot be made.
  DiffReport(std::filesystem::path dir, DiffInputs inputs);
  ~DiffReport();
  DiffReport(const DiffReport&) = delete;
  DiffReport& operator=(const DiffReport&) = delete;

  /// Adds a pair in the order the comparison met it. `expected` and `actual` are the pictures
  /// compared; for a one-sided pair the side it has may be given (it is then shown), the other
  /// is null. Pictures of images and folder pairs are written at once; a video's frames are
  /// kept only while they rank among the kMaxFramesShown that differ most.
  void add(const DiffPair& pair, const Image* expected, const Image* actual);

  /// Writes index.html and puts the folder in place of `dir` (an earlier report there is
  /// replaced). Throws tumble::Error (Environment) when it cannot.
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tumble
