#pragma once
/// What `tumble diff` compared and found, pair by pair, as its reports (the HTML report, the
/// JUnit file) need it: plain data filled in by the command, read by the writers.

#include <optional>
#include <string>

#include "tumble/image_diff.hpp"

namespace tumble {

/// The comparison as a whole: its inputs, as given on the command line, and its tolerances.
struct DiffInputs {
  enum class Kind { Images, Folders, Videos };
  Kind kind = Kind::Images;
  std::string expected, actual;
  DiffTolerance tolerance;
};

/// One pair: two images or two frames compared, or a file or frame that only one side has.
struct DiffPair {
  enum class Side { Both, ExpectedOnly, ActualOnly };
  /// As the stdout line names it: the ACTUAL path for two PNGs, the file name in a folder
  /// pair, `frame_00012` for a video frame.
  std::string name;
  Side side = Side::Both;
  DiffResult result;    ///< the metrics; Side::Both only
  bool beyond = false;  ///< beyond tolerance; always true for a one-sided pair
  /// The stdout line after "NAME: ", without " -- beyond tolerance": the metrics in words, or
  /// for a one-sided pair where it is missing from ("missing from "b/x.png" (only in "a")").
  std::string summary;
  int expected_width = 0, expected_height = 0;  ///< Side::Both only
  int actual_width = 0, actual_height = 0;      ///< Side::Both only
  long frame = -1;                              ///< videos: the frame's index, from 0
  std::optional<double> time_s;  ///< videos: the frame's presentation time, when the file says
  double seconds = 0.0;          ///< time spent reading and comparing this pair (JUnit's time)
};

}  // namespace tumble
