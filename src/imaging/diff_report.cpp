#include "tumble/diff_report.hpp"

#include <fcntl.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

#include "report_page.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/error.hpp"
#include "tumble/png.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

// What marks a folder as a report this command may replace.
constexpr std::string_view kGeneratorMark = "<meta name=\"generator\" content=\"tumble diff\">";

// Appended piece by piece: GCC 12's -Wrestrict misfires on "literal" + std::string here.
std::string in_quotes(const fs::path& p) {
  std::string text(1, '"');
  text += p.string();
  text += '"';
  return text;
}

// ".NAME.SUFFIX" beside `dir`: a dot-name, out of globs, a rename away from `dir`.
fs::path beside(const fs::path& dir, const char* suffix) {
  std::string name(1, '.');
  name += dir.filename().string();
  name += suffix;
  return dir.parent_path() / name;
}

[[noreturn]] void bad(const std::string& message) {
  throw Error(ErrorKind::BadInput, message);
}

[[noreturn]] void cannot(const fs::path& dir, const std::string& why) {
  throw Error(ErrorKind::Environment, "cannot write the report " + in_quotes(dir) + ": " + why);
}

bool is_earlier_report(const fs::path& dir) {
  std::ifstream in(dir / "index.html", std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find(kGeneratorMark) != std::string::npos;
}

// `inner` is `outer` or lies inside it (both made absolute and normal, symlinks resolved where
// they exist).
bool is_within(const fs::path& inner, const fs::path& outer) {
  std::error_code ec;
  const fs::path a = fs::weakly_canonical(fs::absolute(inner), ec);
  const fs::path b = fs::weakly_canonical(fs::absolute(outer), ec);
  auto ai = a.begin();
  for (auto bi = b.begin(); bi != b.end(); ++bi, ++ai) {
    if (bi->empty()) continue;  // a trailing separator
    if (ai == a.end() || *ai != *bi) return false;
  }
  return true;
}

// A file-name-safe stem for the pictures of a pair: letters, digits, '.', '-', '_' kept, the rest
// '_', at most 60 characters, ".png" dropped.
std::string safe_stem(std::string name) {
  if (name.size() > 4) {
    std::string ext = name.substr(name.size() - 4);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](char c) {
      return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    });
    if (ext == ".png") name.resize(name.size() - 4);
  }
  name = fs::path(name).filename().string();  // two PNGs: the pair is named by a path
  std::string out;
  for (const char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == '-' || c == '_';
    out += keep ? c : '_';
    if (out.size() == 60) break;
  }
  return out;
}

// Frames are ranked for a place in the report: beyond tolerance first, then the most differing
// pixels, the largest delta, the lowest PSNR; the earlier frame on a tie, so the choice is
// deterministic.
bool ranks_above(const DiffPair& a, const DiffPair& b) {
  if (a.beyond != b.beyond) return a.beyond;
  if (a.result.differing_pixels != b.result.differing_pixels)
    return a.result.differing_pixels > b.result.differing_pixels;
  if (a.result.largest_delta != b.result.largest_delta)
    return a.result.largest_delta > b.result.largest_delta;
  if (a.result.psnr_db != b.result.psnr_db) return a.result.psnr_db < b.result.psnr_db;
  return a.frame < b.frame;
}

}  // namespace

struct DiffReport::Impl {
  fs::path dir;        // as given, for messages
  fs::path final_dir;  // absolute and normal: where the folder goes
  fs::path temporary;  // beside it, so the rename stays on one file system
  DiffInputs inputs;
  std::vector<DiffPair> pairs;
  std::vector<report::Section> sections;  // images and folders: one per pair, as they came
  struct KeptFrame {
    std::size_t pair;
    Image expected, actual;
  };
  std::vector<KeptFrame> kept;  // videos: the frames ranked highest so far, best first
  bool committed = false;

  report::Picture picture(const Image& image, const std::string& stem, const char* role) {
    const std::string file = stem + (role[0] ? std::string("-") + role : std::string()) + ".png";
    // Small packing: written once, kept as an artifact; several times smaller than Fast.
    write_png(temporary / "images" / file, image, {false, PngOptions::Packing::Small});
    return report::Picture{"images/" + file, image.width, image.height};
  }

  // The section of a pair, its pictures written now.
  report::Section section(std::size_t index, const Image* expected, const Image* actual) {
    const DiffPair& p = pairs[index];
    report::Section s;
    s.pairs = {index};
    s.beyond = p.beyond;
    char number[16];
    std::snprintf(number, sizeof number, "%03zu", index + 1);
    std::string stem = p.frame >= 0 ? std::string() : number + std::string("-");
    stem += safe_stem(p.name);
    if (p.side == DiffPair::Side::Both && expected && actual) {
      s.identical = p.result.largest_delta == 0 && !p.result.size_mismatch;
      if (s.identical) {
        s.expected = picture(*expected, stem, "");
      } else {
        s.expected = picture(*expected, stem, "expected");
        s.actual = picture(*actual, stem, "actual");
        s.diff = picture(diff_image(*expected, *actual, inputs.tolerance.max_delta), stem, "diff");
      }
    } else if (expected) {
      s.expected = picture(*expected, stem, "expected");
    } else if (actual) {
      s.actual = picture(*actual, stem, "actual");
    }
    return s;
  }

  void keep_frame(std::size_t index, const Image& expected, const Image& actual) {
    const DiffPair& p = pairs[index];
    // A frame equal to its counterpart in every channel has nothing to show.
    if (p.result.largest_delta == 0 && !p.result.size_mismatch) return;
    const auto at = std::find_if(kept.begin(), kept.end(),
                                 [&](const KeptFrame& k) { return ranks_above(p, pairs[k.pair]); });
    if (at == kept.end() && kept.size() >= std::size_t(kMaxFramesShown)) return;
    kept.insert(at, KeptFrame{index, expected, actual});
    if (kept.size() > std::size_t(kMaxFramesShown)) kept.pop_back();
  }

  // Videos: the kept frames' sections in rank order, then each run of consecutive frames only
  // one video has as one section.
  void video_sections() {
    for (const KeptFrame& k : kept) sections.push_back(section(k.pair, &k.expected, &k.actual));
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (pairs[i].side == DiffPair::Side::Both) continue;
      report::Section* last = sections.empty() ? nullptr : &sections.back();
      const DiffPair* previous = last ? &pairs[last->pairs.back()] : nullptr;
      if (previous && previous->side == pairs[i].side && previous->frame + 1 == pairs[i].frame) {
        last->pairs.push_back(i);
      } else {
        report::Section s;
        s.pairs = {i};
        s.beyond = true;
        sections.push_back(std::move(s));
      }
    }
  }

  // Puts the finished folder where `final_dir` is. An earlier report there is swapped out in
  // one step where the file system can (renameat2 RENAME_EXCHANGE), else moved aside first.
  void move_into_place() {
    std::error_code ec;
    if (!fs::exists(final_dir)) {
      fs::rename(temporary, final_dir, ec);
      if (ec) cannot(dir, ec.message());
      return;
    }
    if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, final_dir.c_str(), RENAME_EXCHANGE) ==
        0) {
      fs::remove_all(temporary, ec);  // now the earlier report
      return;
    }
    const fs::path aside = beside(final_dir, ".old");
    fs::remove_all(aside, ec);
    fs::rename(final_dir, aside, ec);
    if (ec) cannot(dir, "cannot move the earlier report aside: " + ec.message());
    fs::rename(temporary, final_dir, ec);
    if (ec) {
      std::error_code ignored;
      fs::rename(aside, final_dir, ignored);  // put the earlier one back
      cannot(dir, ec.message());
    }
    fs::remove_all(aside, ec);
  }
};

DiffReport::DiffReport(fs::path dir, DiffInputs inputs) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.dir = dir;
  m.inputs = std::move(inputs);
  m.final_dir = fs::absolute(dir).lexically_normal();
  if (!m.final_dir.has_filename()) m.final_dir = m.final_dir.parent_path();  // "report/"
  const std::string flag = "--report " + in_quotes(dir);
  if (fs::exists(m.final_dir) && !fs::is_directory(m.final_dir))
    bad(flag + " is a file; it names a folder for index.html and its pictures");
  for (const std::string& input : {m.inputs.expected, m.inputs.actual})
    if (is_within(input, m.final_dir))
      bad(flag + " is or holds the input " + in_quotes(input) + "; the report replaces the folder");
  std::error_code ec;
  if (fs::is_directory(m.final_dir, ec) && !fs::is_empty(m.final_dir, ec) &&
      !is_earlier_report(m.final_dir))
    bad(flag + " holds files that are not a tumble diff report; the report replaces the whole " +
        "folder, so give a new or empty one");
  make_output_dir(m.final_dir.parent_path());
  m.temporary = beside(m.final_dir, ".partial");
  fs::remove_all(m.temporary, ec);  // a leftover of an interrupted run
  fs::create_directories(m.temporary / "images", ec);
  if (ec) cannot(dir, ec.message());
}

DiffReport::~DiffReport() {
  if (impl_->committed) return;
  std::error_code ignored;
  fs::remove_all(impl_->temporary, ignored);
}

void DiffReport::add(const DiffPair& pair, const Image* expected, const Image* actual) {
  Impl& m = *impl_;
  m.pairs.push_back(pair);
  const std::size_t index = m.pairs.size() - 1;
  if (m.inputs.kind != DiffInputs::Kind::Videos)
    m.sections.push_back(m.section(index, expected, actual));
  else if (pair.side == DiffPair::Side::Both && expected && actual)
    m.keep_frame(index, *expected, *actual);
}

void DiffReport::commit() {
  Impl& m = *impl_;
  if (m.inputs.kind == DiffInputs::Kind::Videos) m.video_sections();
  // Failures first; otherwise in the order met (file names sorted, frames by rank).
  std::stable_partition(m.sections.begin(), m.sections.end(),
                        [](const report::Section& s) { return s.beyond; });
  write_file_atomically(m.temporary / "index.html",
                        report::page_html(m.inputs, m.pairs, m.sections, kMaxFramesShown));
  m.move_into_place();
  m.committed = true;
}

}  // namespace tumble
