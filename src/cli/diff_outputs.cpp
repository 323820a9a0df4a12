#include "diff_outputs.hpp"

#include <system_error>

#include "tumble/atomic_file.hpp"
#include "tumble/error.hpp"
#include "tumble/junit_xml.hpp"
#include "tumble/png.hpp"

namespace tumble::cli {

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return std::filesystem::equivalent(a, b, ec) && !ec;
}

namespace {

namespace fs = std::filesystem;

// `file` is an input, or one of the PNGs a folder input holds.
bool is_compared(const fs::path& file, const fs::path& input) {
  if (same_file(file, input)) return true;
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  const fs::path folder = file.has_parent_path() ? file.parent_path() : fs::path(".");
  return ext == ".png" && fs::is_directory(input) && same_file(folder, input);
}

}  // namespace

DiffOutputs::DiffOutputs(const DiffOptions& o, DiffInputs inputs)
    : inputs_(std::move(inputs)), junit_(o.junit) {
  if (!junit_.empty()) {
    const std::string flag = "--junit \"" + junit_ + "\"";
    if (fs::is_directory(junit_)) throw Error(ErrorKind::BadInput, flag + " is a folder");
    if (is_compared(junit_, inputs_.expected) || is_compared(junit_, inputs_.actual))
      throw Error(ErrorKind::BadInput, flag + " would overwrite an input");
  }
  if (!o.report.empty()) report_ = std::make_unique<DiffReport>(o.report, inputs_);
}

void DiffOutputs::add(DiffPair pair, const Image* expected, const Image* actual) {
  // A pair's time is everything since the previous one: reading, decoding, comparing it.
  const Clock::time_point now = Clock::now();
  pair.seconds = std::chrono::duration<double>(now - last_).count();
  last_ = now;
  if (report_) report_->add(pair, expected, actual);
  if (!junit_.empty()) pairs_.push_back(std::move(pair));
}

void DiffOutputs::compared(const std::string& name, const DiffResult& result, bool beyond,
                           const std::string& summary, const Image& expected, const Image& actual,
                           long frame, std::optional<double> time_s) {
  if (!report_ && junit_.empty()) return;
  DiffPair pair;
  pair.name = name;
  pair.result = result;
  pair.beyond = beyond;
  pair.summary = summary;
  pair.expected_width = expected.width;
  pair.expected_height = expected.height;
  pair.actual_width = actual.width;
  pair.actual_height = actual.height;
  pair.frame = frame;
  pair.time_s = time_s;
  add(std::move(pair), &expected, &actual);
}

void DiffOutputs::one_sided(const std::string& name, const std::string& summary,
                            DiffPair::Side side, const fs::path& present) {
  if (!report_ && junit_.empty()) return;
  DiffPair pair;
  pair.name = name;
  pair.side = side;
  pair.beyond = true;
  pair.summary = summary;
  // The report shows the file that is there; one that does not decode is only named (the
  // comparison never needed it, so it is no error).
  std::optional<Image> image;
  if (report_) {
    try {
      image = read_png(present);
    } catch (const Error&) {
    }
  }
  const Image* shown = image ? &*image : nullptr;
  add(std::move(pair), side == DiffPair::Side::ExpectedOnly ? shown : nullptr,
      side == DiffPair::Side::ActualOnly ? shown : nullptr);
}

void DiffOutputs::one_sided_frames(long first_frame, long count, const std::string& summary,
                                   DiffPair::Side side) {
  if (!report_ && junit_.empty()) return;
  for (long k = first_frame; k < first_frame + count; ++k) {
    DiffPair pair;
    pair.name = frame_stem(k);
    pair.side = side;
    pair.beyond = true;
    pair.summary = summary;
    pair.frame = k;
    add(std::move(pair), nullptr, nullptr);
  }
}

void DiffOutputs::finish() {
  if (report_) report_->commit();
  if (!junit_.empty()) {
    const fs::path file = junit_;
    if (file.has_parent_path()) make_output_dir(file.parent_path());
    write_file_atomically(file, junit_xml(inputs_, pairs_, seconds_since(start_)));
  }
}

}  // namespace tumble::cli
