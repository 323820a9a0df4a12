#include "report_page.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tumble/markup_text.hpp"

namespace tumble::report {
namespace {

// Everything the page needs is inline, and the Content-Security-Policy says so to the browser:
// no request leaves the report folder (img-src 'self': the pictures beside index.html), so a
// name that slipped through escaping still could not fetch anything.
constexpr const char* kContentSecurityPolicy =
    "default-src 'none'; img-src 'self'; style-src 'unsafe-inline'; script-src 'unsafe-inline'";

// System fonts only (no web font to fetch); pixelated scaling, so that one changed pixel of a
// 160x120 golden is a visible square rather than a blur.
constexpr const char* kStyle = R"css(
:root{--fail:#b00020;--pass:#1b7a3a;--muted:#5f6368;--line:#dadce0}
*{box-sizing:border-box}
body{margin:0;font:15px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,Arial,sans-serif;color:#202124;background:#f6f7f8}
header,main{max-width:1100px;margin:0 auto;padding:0 16px}
header{padding-top:16px}
h1{font-size:20px;margin:0 0 4px}
.summary{font-size:18px;font-weight:600;margin:4px 0}
.inputs,.note{color:var(--muted);margin:2px 0}
code{font:13px ui-monospace,Menlo,Consolas,monospace;word-break:break-all}
.toc{list-style:none;padding:0;margin:12px 0;display:flex;flex-wrap:wrap;gap:6px}
.toc a{display:inline-block;padding:1px 8px;border:1px solid var(--line);border-radius:12px;background:#fff;color:inherit;text-decoration:none;word-break:break-all}
.badge{display:inline-block;min-width:3.4em;padding:0 6px;border-radius:4px;color:#fff;font-size:12px;font-weight:700;text-align:center;letter-spacing:.04em;vertical-align:2px}
.badge.fail{background:var(--fail)}.badge.pass{background:var(--pass)}
section.pair{background:#fff;border:1px solid var(--line);border-left:6px solid var(--pass);border-radius:6px;margin:16px 0;padding:12px 16px}
section.pair.fail{border-left-color:var(--fail)}
h2{font-size:17px;margin:0 0 6px;word-break:break-all}
.why{margin:0 0 6px;color:var(--fail);font-weight:600}
table.metrics{border-collapse:collapse;margin:0 0 12px}
.metrics th,.metrics td{text-align:left;padding:1px 16px 1px 0;vertical-align:top}
.metrics th{font-weight:500;color:var(--muted)}
.metrics td.bad{color:var(--fail);font-weight:600}
.compare{margin:0 0 12px}
.stage{position:relative;max-width:100%;overflow:hidden;line-height:0;cursor:ew-resize;touch-action:none;background:repeating-linear-gradient(45deg,#e8e8e8 0 6px,#fff 6px 12px)}
.stage img{position:absolute;left:0;top:0;height:auto;image-rendering:pixelated;user-select:none;-webkit-user-drag:none}
.stage img.actual{clip-path:inset(0 0 0 var(--split,50%))}
.stage .line{position:absolute;top:0;bottom:0;left:var(--split,50%);width:2px;margin-left:-1px;background:#ffd600;box-shadow:0 0 0 1px rgba(0,0,0,.45);pointer-events:none}
.controls{display:flex;flex-wrap:wrap;align-items:center;gap:6px 14px;margin-top:6px}
.controls input{width:260px}
.controls output{color:var(--muted)}
button{font:inherit;padding:2px 12px;border:1px solid #80868b;border-radius:4px;background:#f1f3f4;cursor:pointer}
:focus-visible{outline:3px solid #1a73e8;outline-offset:2px}
.pictures{display:grid;grid-template-columns:repeat(3,minmax(0,1fr));gap:12px}
.pictures.one{grid-template-columns:minmax(0,360px)}
figure{margin:0}
figure img{display:block;width:100%;height:auto;image-rendering:pixelated;border:1px solid var(--line)}
figcaption{color:var(--muted);font-size:13px}
)css";

// The in-place compare: the slider moves the line (left of it expected, right of it actual);
// the button shows one whole picture, then the other (a blink compare). Both are native
// controls, so arrows, Home/End, Page Up/Down, Space and Enter work without extra code; the
// picture itself follows a pointer drag.
constexpr const char* kScript = R"js(
"use strict";
document.querySelectorAll(".compare").forEach(function (box) {
  var stage = box.querySelector(".stage"), range = box.querySelector("input"),
      toggle = box.querySelector("button"), state = box.querySelector("output");
  function show(value) {
    var v = Math.max(0, Math.min(100, Math.round(value)));
    var text = v >= 100 ? "showing expected" : v <= 0 ? "showing actual" :
        "expected left of the line, actual right of it";
    range.value = String(v);
    range.setAttribute("aria-valuetext", text);
    stage.style.setProperty("--split", v + "%");
    state.textContent = text;
    toggle.textContent = v > 0 ? "Show actual" : "Show expected";
  }
  function follow(event) {
    var r = stage.getBoundingClientRect();
    show(100 * (event.clientX - r.left) / r.width);
  }
  range.addEventListener("input", function () { show(Number(range.value)); });
  toggle.addEventListener("click", function () { show(Number(range.value) > 0 ? 0 : 100); });
  stage.addEventListener("pointerdown", function (event) {
    stage.setPointerCapture(event.pointerId);
    follow(event);
  });
  stage.addEventListener("pointermove", function (event) {
    if (stage.hasPointerCapture(event.pointerId)) follow(event);
  });
  show(Number(range.value));
});
)js";

std::string text(std::string_view s) {
  return escape_markup_text(s);
}
std::string attr(std::string_view s) {
  return escape_markup_attribute(s);
}

std::string number(double value) {
  char out[32];
  std::snprintf(out, sizeof out, "%g", value);
  return out;
}

// As the stdout line writes it: three significant digits, never "100%" unless every pixel
// differs.
std::string share_text(const DiffResult& r) {
  const double percent = 100.0 * r.fraction;
  if (r.differing_pixels < r.total_pixels && percent >= 99.95) return "&gt;99.9%";
  char out[32];
  std::snprintf(out, sizeof out, "%.3g%%", percent);
  return out;
}

std::string psnr_text(double psnr_db) {
  if (std::isinf(psnr_db)) return "identical";
  char out[32];
  std::snprintf(out, sizeof out, "%.2f dB", psnr_db);
  return out;
}

std::string time_text(double seconds) {
  char out[32];
  std::snprintf(out, sizeof out, "%.3f s", seconds);
  return out;
}

std::string size_text(int width, int height) {
  return std::to_string(width) + "\xC3\x97" + std::to_string(height);  // U+00D7 ×
}

std::string tolerance_text(const DiffTolerance& t) {
  std::string s = "max delta " + std::to_string(t.max_delta) + ", max fraction " +
                  number(t.max_fraction) + ", min PSNR ";
  s += t.min_psnr_db ? number(*t.min_psnr_db) + " dB" : std::string("none");
  return s;
}

bool psnr_too_low(const DiffPair& p, const DiffTolerance& t) {
  return t.min_psnr_db && !(p.result.psnr_db >= *t.min_psnr_db);
}

// "frames 15 to 29" / "frame 12"; images and files by their name.
std::string section_title(const std::vector<DiffPair>& pairs, const Section& s) {
  const DiffPair& first = pairs[s.pairs.front()];
  if (first.frame < 0) return first.name;
  if (s.pairs.size() == 1) return "frame " + std::to_string(first.frame);
  return "frames " + std::to_string(first.frame) + " to " +
         std::to_string(pairs[s.pairs.back()].frame);
}

// What made a pair fail, in words, for the line under its title.
std::string why_text(const DiffInputs& in, const std::vector<DiffPair>& pairs, const Section& s) {
  const DiffPair& p = pairs[s.pairs.front()];
  const std::string& side_name = p.side == DiffPair::Side::ExpectedOnly ? in.expected : in.actual;
  const std::string& other = p.side == DiffPair::Side::ExpectedOnly ? in.actual : in.expected;
  if (p.side != DiffPair::Side::Both) {
    if (p.frame >= 0)
      return "only in " + text(side_name) + " (" + std::to_string(s.pairs.size()) +
             (s.pairs.size() == 1 ? " frame" : " frames") + " the other video does not have)";
    return "only in " + text(side_name) + ", missing from " + text(other);
  }
  std::vector<std::string> reasons;
  if (p.result.size_mismatch) reasons.push_back("the sizes differ");
  if (!p.result.size_mismatch && p.result.fraction > in.tolerance.max_fraction)
    reasons.push_back(share_text(p.result) + " of the pixels differ, more than the " +
                      number(100.0 * in.tolerance.max_fraction) + "% allowed");
  if (psnr_too_low(p, in.tolerance))
    reasons.push_back("PSNR " + psnr_text(p.result.psnr_db) + " is below the " +
                      number(*in.tolerance.min_psnr_db) + " dB required");
  std::string out = "beyond tolerance: ";
  for (std::size_t i = 0; i < reasons.size(); ++i) out += (i ? "; " : "") + reasons[i];
  return out;
}

void metric_row(std::string& html, const char* what, const std::string& value,
                const std::string& limit, bool bad) {
  html += "<tr><th>" + std::string(what) + "</th><td" + (bad ? " class=\"bad\"" : "") + ">" +
          value + "</td><td>" + limit + "</td></tr>\n";
}

void metrics_table(std::string& html, const DiffInputs& in, const DiffPair& p) {
  const DiffResult& r = p.result;
  const DiffTolerance& t = in.tolerance;
  html += "<table class=\"metrics\">\n";
  if (p.time_s)
    metric_row(html, "time", time_text(*p.time_s) + " (frame " + std::to_string(p.frame) + ")", "",
               false);
  const bool sizes_differ = r.size_mismatch;
  metric_row(html, "size",
             sizes_differ ? size_text(p.expected_width, p.expected_height) + " expected, " +
                                size_text(p.actual_width, p.actual_height) + " actual"
                          : size_text(p.expected_width, p.expected_height),
             "must be equal", sizes_differ);
  const long allowed = static_cast<long>(std::floor(t.max_fraction * double(r.total_pixels)));
  metric_row(html, "differing pixels",
             std::to_string(r.differing_pixels) + " of " + std::to_string(r.total_pixels) + " (" +
                 share_text(r) + ")",
             t.max_fraction > 0.0
                 ? "at most " + number(100.0 * t.max_fraction) + "% (" + std::to_string(allowed) +
                       (allowed == 1 ? " pixel)" : " pixels)")
                 : std::string("none allowed"),
             !sizes_differ && r.fraction > t.max_fraction);
  metric_row(html, "largest delta", std::to_string(r.largest_delta) + " of 255",
             "a pixel differs when a channel is off by more than " + std::to_string(t.max_delta),
             false);
  metric_row(
      html, "PSNR", psnr_text(r.psnr_db),
      t.min_psnr_db ? "at least " + number(*t.min_psnr_db) + " dB" : std::string("no minimum"),
      psnr_too_low(p, t));
  html += "</table>\n";
}

std::string img(const Picture& pic, const char* alt, const std::string& extra = {}) {
  return "<img src=\"" + attr(pic.src) + "\" width=\"" + std::to_string(pic.width) +
         "\" height=\"" + std::to_string(pic.height) + "\" alt=\"" + alt + "\"" + extra + ">";
}

std::string figure(const Picture& pic, const char* caption) {
  return "<figure>" + img(pic, caption) + "<figcaption>" + caption + "</figcaption></figure>\n";
}

std::string percent(int part, int whole) {
  char out[32];
  std::snprintf(out, sizeof out, "%.4g%%", 100.0 * part / whole);
  return out;
}

// The expected and actual pictures stacked on one canvas (the larger width × the larger
// height, top-left aligned, as compare_images aligns them), at the smallest integer zoom (at
// most 8) that makes it 480 pixels wide: a 160x120 golden's pixels become 3x3 squares.
void compare_block(std::string& html, const Picture& expected, const Picture& actual) {
  const int width = std::max(expected.width, actual.width);
  const int height = std::max(expected.height, actual.height);
  const int zoom = std::clamp((480 + width - 1) / std::max(width, 1), 1, 8);
  html += "<div class=\"compare\">\n<div class=\"stage\" style=\"width:" +
          std::to_string(zoom * width) + "px;aspect-ratio:" + std::to_string(width) + "/" +
          std::to_string(height) + "\">";
  html += img(expected, "expected",
              " class=\"expected\" style=\"width:" + percent(expected.width, width) + "\"");
  html += img(actual, "actual",
              " class=\"actual\" style=\"width:" + percent(actual.width, width) + "\"");
  html += "<div class=\"line\"></div></div>\n";
  html +=
      "<div class=\"controls\"><input type=\"range\" min=\"0\" max=\"100\" step=\"1\" "
      "value=\"50\" aria-label=\"Swipe: expected left of the line, actual right of it\">"
      "<button type=\"button\">Show expected</button>"
      "<output>expected left of the line, actual right of it</output></div>\n</div>\n";
}

void section_html(std::string& html, const DiffInputs& in, const std::vector<DiffPair>& pairs,
                  const Section& s, std::size_t index) {
  const DiffPair& p = pairs[s.pairs.front()];
  html += "<section class=\"pair " + std::string(s.beyond ? "fail" : "pass") + "\" id=\"s" +
          std::to_string(index + 1) + "\" data-name=\"" + attr(p.name) + "\">\n";
  html += "<h2><span class=\"badge " + std::string(s.beyond ? "fail\">FAIL" : "pass\">PASS") +
          "</span> " + text(section_title(pairs, s)) + "</h2>\n";
  if (s.beyond) html += "<p class=\"why\">" + why_text(in, pairs, s) + "</p>\n";
  if (p.side == DiffPair::Side::Both) {
    metrics_table(html, in, p);
  } else {
    html += "<p class=\"note\">" + text(p.summary) + "</p>\n";
  }
  if (s.expected && s.actual && s.diff) {
    compare_block(html, *s.expected, *s.actual);
    html += "<div class=\"pictures\">\n" + figure(*s.expected, "expected") +
            figure(*s.actual, "actual") + figure(*s.diff, "diff") + "</div>\n";
  } else if (s.expected || s.actual) {
    const char* caption = s.identical ? "expected = actual" : s.expected ? "expected" : "actual";
    html += "<div class=\"pictures one\">\n" +
            figure(s.expected ? *s.expected : *s.actual, caption) + "</div>\n";
  }
  html += "</section>\n";
}

// "0-4, 9, 15-29": the failing frames as ranges.
std::string frame_ranges(const std::vector<DiffPair>& pairs) {
  std::vector<long> frames;
  for (const DiffPair& p : pairs)
    if (p.beyond) frames.push_back(p.frame);
  std::sort(frames.begin(), frames.end());
  std::string out;
  for (std::size_t i = 0; i < frames.size();) {
    std::size_t j = i;
    while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
    if (!out.empty()) out += ", ";
    out += std::to_string(frames[i]);
    if (j > i) out += "\xE2\x80\x93" + std::to_string(frames[j]);  // U+2013 en dash
    i = j + 1;
  }
  return out;
}

}  // namespace

std::string page_html(const DiffInputs& in, const std::vector<DiffPair>& pairs,
                      const std::vector<Section>& sections, int frames_limit) {
  long failed = 0, expected_frames = 0, actual_frames = 0;
  int worst_delta = 0;
  bool any_compared = false;
  for (const DiffPair& p : pairs) {
    failed += p.beyond ? 1 : 0;
    if (p.side != DiffPair::Side::ActualOnly) ++expected_frames;
    if (p.side != DiffPair::Side::ExpectedOnly) ++actual_frames;
    if (p.side == DiffPair::Side::Both) {
      any_compared = true;
      worst_delta = std::max(worst_delta, p.result.largest_delta);
    }
  }
  const std::string summary = std::to_string(pairs.size()) +
                              (pairs.size() == 1 ? " pair, " : " pairs, ") +
                              std::to_string(failed) + " failed, worst delta " +
                              (any_compared ? std::to_string(worst_delta) : std::string("none"));
  const char* kind = in.kind == DiffInputs::Kind::Images    ? "two images"
                     : in.kind == DiffInputs::Kind::Folders ? "two folders of PNGs"
                                                            : "two videos, frame by frame";

  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<meta name=\"generator\" content=\"tumble diff\">\n";
  html += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  html += "<meta http-equiv=\"Content-Security-Policy\" content=\"" +
          std::string(kContentSecurityPolicy) + "\">\n";
  html += "<title>tumble diff: " + std::string(failed > 0 ? "FAIL" : "PASS") + ", " +
          text(summary) + "</title>\n";
  html += "<style>" + std::string(kStyle) + "</style>\n</head>\n<body>\n<header>\n";
  html += "<h1>tumble diff <span class=\"badge " +
          std::string(failed > 0 ? "fail\">FAIL" : "pass\">PASS") + "</span></h1>\n";
  html += "<p class=\"summary\" id=\"summary\">" + text(summary) + "</p>\n";
  html += "<p class=\"inputs\">" + std::string(kind) + ": expected <code>" + text(in.expected) +
          "</code>, actual <code>" + text(in.actual) + "</code></p>\n";
  html += "<p class=\"inputs\">tolerance: " + tolerance_text(in.tolerance) + "</p>\n";
  if (in.kind == DiffInputs::Kind::Videos) {
    long shown = 0;
    for (const Section& s : sections)
      if (pairs[s.pairs.front()].side == DiffPair::Side::Both) ++shown;
    std::string note = "frames: " + std::to_string(expected_frames) + " expected, " +
                       std::to_string(actual_frames) + " actual. ";
    if (shown == 0)
      note += "Every compared frame is identical, so none is shown.";
    else
      note += "Shown: the " + std::to_string(shown) + (shown == 1 ? " frame" : " frames") +
              " that differ most (at most " + std::to_string(frames_limit) + ").";
    if (failed > 0) note += " Failing frames: " + frame_ranges(pairs) + ".";
    html += "<p class=\"note\">" + note + "</p>\n";
  }
  html += "<nav><ol class=\"toc\">\n";
  for (std::size_t i = 0; i < sections.size(); ++i)
    html += "<li><a href=\"#s" + std::to_string(i + 1) + "\"><span class=\"badge " +
            (sections[i].beyond ? "fail\">FAIL" : "pass\">PASS") + "</span> " +
            text(section_title(pairs, sections[i])) + "</a></li>\n";
  html += "</ol></nav>\n</header>\n<main>\n";
  for (std::size_t i = 0; i < sections.size(); ++i) section_html(html, in, pairs, sections[i], i);
  html += "</main>\n<script>" + std::string(kScript) + "</script>\n</body>\n</html>\n";
  return html;
}

}  // namespace tumble::report
