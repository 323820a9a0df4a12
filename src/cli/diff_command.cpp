// tumble diff: two PNGs, two folders of PNGs (paired by file name) or two videos (frame by frame)
// compared within tolerances. One line per pair on stdout, a one-line verdict at the end, and
// with --diff-out a diff picture for every pair beyond tolerance; --report and --junit through
// DiffOutputs. Exit 0 within tolerance, 1 beyond it; a missing or undecodable input is a
// tumble::Error (exit 2) naming the file.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>
#include <system_error>

#include "commands.hpp"
#include "diff_outputs.hpp"
#include "progress.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/error.hpp"
#include "tumble/image_diff.hpp"
#include "tumble/png.hpp"
#include "tumble/video_reader.hpp"

namespace tumble::cli {
namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& p) {
  return "\"" + p.string() + "\"";
}

// %g: "0", "0.001", "40" — as the user typed them, not "0.001000".
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

enum class InputKind { Png, Folder, Video };

bool has_png_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png";
}

// A folder is a folder of PNGs; a file named *.png (any case) is a PNG; any other file is handed
// to FFmpeg as a video, whose own probing decides what it is (and fails with the file named).
InputKind kind_of(const fs::path& p) {
  if (fs::is_directory(p)) return InputKind::Folder;
  return has_png_extension(p) ? InputKind::Png : InputKind::Video;
}

const char* kind_name(InputKind kind) {
  switch (kind) {
    case InputKind::Png:
      return "a PNG image";
    case InputKind::Folder:
      return "a folder";
    case InputKind::Video:
      return "a video";
  }
  return "";
}

// The PNG files directly in `dir` (not in sub-folders), by file name.
std::set<std::string> png_names(const fs::path& dir) {
  std::set<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (has_png_extension(it->path()) && it->is_regular_file())
      names.insert(it->path().filename().string());
  if (ec) bad("cannot list the folder " + quoted(dir) + ": " + ec.message());
  return names;
}

// Counts the pairs, prints one line per pair and writes the diff pictures.
class Comparison {
 public:
  Comparison(const DiffOptions& o, const DiffTolerance& tolerance, DiffOutputs& outputs)
      : options_(o), tolerance_(tolerance), outputs_(outputs) {}

  // Compares one pair; `diff_path` (empty: none) receives the diff picture when it is beyond
  // tolerance. `frame` and `time_s`: a video frame's index and presentation time.
  void compare(const std::string& name, const Image& expected, const Image& actual,
               const fs::path& diff_path, long frame = -1, std::optional<double> time_s = {}) {
    const DiffResult r = compare_images(expected, actual, tolerance_.max_delta);
    const bool beyond = !r.within(tolerance_);
    ++pairs_;
    if (beyond) ++beyond_;
    std::string line = name + ": ";
    if (r.size_mismatch) {
      line +=
          "sizes differ: " + size_text(expected) + " expected, " + size_text(actual) + " actual";
    } else {
      char text[160];
      std::snprintf(text, sizeof text, "%ld of %ld pixels differ (%s), largest delta %d, ",
                    r.differing_pixels, r.total_pixels, share_text(r).c_str(), r.largest_delta);
      line += text;
      if (std::isinf(r.psnr_db)) {
        line += "identical";
      } else {
        std::snprintf(text, sizeof text, "PSNR %.2f dB", r.psnr_db);
        line += text;
      }
    }
    // The report and the JUnit file carry the same words as stdout: the line after "NAME: ".
    outputs_.compared(name, r, beyond, line.substr(name.size() + 2), expected, actual, frame,
                      time_s);
    if (beyond) {
      line += " -- beyond tolerance";
      if (!diff_path.empty()) {
        // Folders and videos: the --diff-out folder is made (an output folder, like --out); a
        // PNG file's folder must exist (output_target.hpp: tumble creates only output folders).
        if (diff_path != fs::path(options_.diff_out)) make_output_dir(options_.diff_out);
        write_png(diff_path, diff_image(expected, actual, tolerance_.max_delta));
        line += "; diff image " + diff_path.string();
      }
    }
    std::printf("%s\n", line.c_str());
  }

  // A file only one folder has, `present`: always beyond tolerance, nothing to draw.
  void unmatched(const std::string& name, const std::string& where, DiffPair::Side side,
                 const fs::path& present) {
    outputs_.one_sided(name, where, side, present);
    print_unmatched(name + ": " + where, 1);
  }
  // `count` frames from `first` that only one video has.
  void unmatched_frames(long first, long count, const std::string& where, DiffPair::Side side) {
    outputs_.one_sided_frames(first, count, where, side);
    print_unmatched(frame_stem(first) + (count > 1 ? " to " + frame_stem(first + count - 1) : "") +
                        ": " + where,
                    count);
  }

  // "tumble diff: 2 of 30 frames differ beyond tolerance (max delta 0, max fraction 0)"; `what`
  // names the pairs ("frames", "files"; empty: one pair of images); `note` is appended when not
  // empty. Returns the exit code.
  int verdict(const std::string& what, const std::string& note = {}) const {
    std::string text = "tumble diff: ";
    if (what.empty())
      text +=
          beyond_ > 0 ? "the images differ beyond tolerance" : "the images are within tolerance";
    else if (beyond_ > 0)
      text += std::to_string(beyond_) + " of " + std::to_string(pairs_) + " " + what +
              " differ beyond tolerance";
    else
      text += "all " + std::to_string(pairs_) + " " + what + " within tolerance";
    text += " (max delta " + std::to_string(tolerance_.max_delta) + ", max fraction " +
            number(tolerance_.max_fraction);
    if (tolerance_.min_psnr_db) text += ", min PSNR " + number(*tolerance_.min_psnr_db) + " dB";
    text += ")";
    if (!note.empty()) text += "; " + note;
    std::printf("%s\n", text.c_str());
    std::fflush(stdout);
    return beyond_ > 0 ? 1 : 0;
  }

  const DiffOptions& options() const { return options_; }

 private:
  // Three significant digits, but never "100%" unless every pixel differs.
  static std::string share_text(const DiffResult& r) {
    const double percent = 100.0 * r.fraction;
    if (r.differing_pixels < r.total_pixels && percent >= 99.95) return ">99.9%";
    char text[32];
    std::snprintf(text, sizeof text, "%.3g%%", percent);
    return text;
  }
  static std::string size_text(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
  }

  void print_unmatched(const std::string& line, long count) {
    pairs_ += count;
    beyond_ += count;
    std::printf("%s -- beyond tolerance\n", line.c_str());
  }

  const DiffOptions& options_;
  DiffTolerance tolerance_;
  DiffOutputs& outputs_;
  long pairs_ = 0;
  long beyond_ = 0;
};

int diff_images(Comparison& c, const fs::path& expected, const fs::path& actual) {
  const fs::path diff_out = c.options().diff_out;
  if (!diff_out.empty() && fs::is_directory(diff_out))
    bad("--diff-out " + quoted(diff_out) +
        " is a folder; comparing two images it names a PNG file");
  if (!diff_out.empty() && (same_file(diff_out, expected) || same_file(diff_out, actual)))
    bad("--diff-out " + quoted(diff_out) + " would overwrite an input");
  const Image e = read_png(expected);
  const Image a = read_png(actual);
  c.compare(actual.string(), e, a, diff_out);
  return c.verdict("");
}

void check_diff_folder(const fs::path& diff_out, const fs::path& expected, const fs::path& actual) {
  if (diff_out.empty()) return;
  if (fs::exists(diff_out) && !fs::is_directory(diff_out))
    bad("--diff-out " + quoted(diff_out) +
        " is a file; comparing folders or videos it names a folder for one PNG per differing pair");
  if (same_file(diff_out, expected) || same_file(diff_out, actual))
    bad("--diff-out " + quoted(diff_out) + " is an input folder; its PNGs would be overwritten");
}

int diff_folders(Comparison& c, const fs::path& expected, const fs::path& actual) {
  const fs::path diff_out = c.options().diff_out;
  check_diff_folder(diff_out, expected, actual);
  const std::set<std::string> in_expected = png_names(expected);
  const std::set<std::string> in_actual = png_names(actual);
  std::set<std::string> all = in_expected;
  all.insert(in_actual.begin(), in_actual.end());
  // Two empty folders would pass vacuously: a render that wrote nothing must not look approved.
  if (all.empty())
    bad("no PNG files in " + quoted(expected) + " or " + quoted(actual) + " to compare");
  for (const std::string& name : all) {
    if (!in_actual.count(name)) {
      c.unmatched(name,
                  "missing from " + quoted(actual / name) + " (only in " + quoted(expected) + ")",
                  DiffPair::Side::ExpectedOnly, expected / name);
    } else if (!in_expected.count(name)) {
      c.unmatched(name,
                  "missing from " + quoted(expected / name) + " (only in " + quoted(actual) + ")",
                  DiffPair::Side::ActualOnly, actual / name);
    } else {
      const Image e = read_png(expected / name);
      const Image a = read_png(actual / name);
      c.compare(name, e, a, diff_out.empty() ? fs::path() : diff_out / name);
    }
  }
  return c.verdict("files");
}

int diff_videos(Comparison& c, const fs::path& expected, const fs::path& actual) {
  const fs::path diff_out = c.options().diff_out;
  check_diff_folder(diff_out, expected, actual);
  VideoReader expected_video(expected);
  VideoReader actual_video(actual);
  Image e, a;
  long frames = 0;
  for (;; ++frames) {
    const bool have_e = expected_video.next(e);
    const bool have_a = actual_video.next(a);
    if (!have_e || !have_a) {
      // Count what the longer one still holds, so the verdict says by how much they differ.
      long expected_frames = frames + (have_e ? 1 : 0), actual_frames = frames + (have_a ? 1 : 0);
      while (have_e && expected_video.next(e)) ++expected_frames;
      while (have_a && actual_video.next(a)) ++actual_frames;
      if (expected_frames == actual_frames) break;
      const long extra = std::abs(expected_frames - actual_frames);
      const bool expected_longer = expected_frames > actual_frames;
      c.unmatched_frames(
          frames, extra, "only in " + quoted(expected_longer ? expected : actual),
          expected_longer ? DiffPair::Side::ExpectedOnly : DiffPair::Side::ActualOnly);
      return c.verdict("frames", "frame counts differ: " + std::to_string(expected_frames) +
                                     " expected, " + std::to_string(actual_frames) + " actual");
    }
    const std::string name = frame_stem(frames);
    c.compare(name, e, a, diff_out.empty() ? fs::path() : diff_out / (name + ".png"), frames,
              expected_video.frame_time_s());
  }
  if (frames == 0)
    bad("no frames in " + quoted(expected) + " or " + quoted(actual) + " to compare");
  return c.verdict("frames");
}

}  // namespace

void add_diff_command(CLI::App& app, DiffOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "diff",
      "Compare two PNGs, two folders of PNGs (paired by file name) or two videos (frame by "
      "frame). Exit 0 within tolerance, 1 beyond it, 2 when an input is missing or unreadable");
  cmd->add_option("expected", o.expected, "The approved image, folder or video")->required();
  cmd->add_option("actual", o.actual, "The image, folder or video to check")->required();
  cmd->add_option("--max-delta", o.max_delta,
                  "Largest per-channel difference (0-255) that still counts as equal (default 0)");
  cmd->add_option("--max-fraction", o.max_fraction,
                  "Share of pixels (0-1) allowed to differ by more than --max-delta (default 0)");
  cmd->add_option("--min-psnr", o.min_psnr_db,
                  "Smallest PSNR in dB a pair may have (default: none)");
  cmd->add_option("--diff-out", o.diff_out,
                  "Write a diff picture (grey: equal, magenta: changed) for each pair beyond "
                  "tolerance, and only for those: a PNG file for two images, a folder of "
                  "<name>.png for folders and videos");
  cmd->add_option("--report", o.report,
                  "Write an HTML report into this folder (index.html and the pictures it shows; "
                  "opens from disk, fetches nothing): every pair's verdict and metrics, failures "
                  "first, with expected, actual, diff and a swipe compare; written whatever the "
                  "verdict");
  cmd->add_option("--junit", o.junit,
                  "Write JUnit XML to this file for CI dashboards: one testcase per pair, a "
                  "failure with the metrics for each pair beyond tolerance; written whatever the "
                  "verdict");
}

int run_diff(const DiffOptions& o) {
  if (o.max_delta < 0 || o.max_delta > 255)
    bad("--max-delta must be an integer in [0, 255]; got " + std::to_string(o.max_delta));
  if (!std::isfinite(o.max_fraction) || o.max_fraction < 0.0 || o.max_fraction > 1.0)
    bad("--max-fraction must be a share of pixels in [0, 1]; got " + number(o.max_fraction));
  if (o.min_psnr_db && (!std::isfinite(*o.min_psnr_db) || *o.min_psnr_db < 0.0))
    bad("--min-psnr must be a finite number of dB, at least 0; got " + number(*o.min_psnr_db));

  const fs::path expected = o.expected, actual = o.actual;
  for (const fs::path& p : {expected, actual})
    if (!fs::exists(p)) bad("no such file or folder: " + quoted(p));
  const InputKind kind = kind_of(expected);
  if (kind_of(actual) != kind)
    bad("cannot compare " + quoted(expected) + " (" + kind_name(kind) + ") with " + quoted(actual) +
        " (" + kind_name(kind_of(actual)) +
        "): give two PNG files, two folders of PNGs or two videos");

  const DiffTolerance tolerance{o.max_delta, o.max_fraction, o.min_psnr_db};
  DiffOutputs outputs(o, DiffInputs{kind == InputKind::Png      ? DiffInputs::Kind::Images
                                    : kind == InputKind::Folder ? DiffInputs::Kind::Folders
                                                                : DiffInputs::Kind::Videos,
                                    o.expected, o.actual, tolerance});
  Comparison comparison(o, tolerance, outputs);
  int exit_code = 0;
  switch (kind) {
    case InputKind::Png:
      exit_code = diff_images(comparison, expected, actual);
      break;
    case InputKind::Folder:
      exit_code = diff_folders(comparison, expected, actual);
      break;
    case InputKind::Video:
      exit_code = diff_videos(comparison, expected, actual);
      break;
  }
  // Whatever the verdict: a failing job is when the report is wanted most.
  outputs.finish();
  return exit_code;
}

}  // namespace tumble::cli
