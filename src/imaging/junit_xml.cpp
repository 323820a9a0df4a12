#include "tumble/junit_xml.hpp"

#include <cstdio>

#include "tumble/markup_text.hpp"

namespace tumble {
namespace {

// %g: "0", "0.001", "40" — as the user typed them.
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// Milliseconds are what the dashboards show; more digits would only be noise.
std::string duration(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", seconds < 0.0 ? 0.0 : seconds);
  return text;
}

std::string attribute(const char* name, const std::string& value) {
  return std::string(" ") + name + "=\"" + escape_markup_attribute(value) + "\"";
}

std::string tolerance_text(const DiffTolerance& t) {
  std::string text =
      "max delta " + std::to_string(t.max_delta) + ", max fraction " + number(t.max_fraction);
  if (t.min_psnr_db) text += ", min PSNR " + number(*t.min_psnr_db) + " dB";
  return text;
}

// The failure's body: what a person reads in the dashboard's detail view.
std::string failure_details(const DiffInputs& inputs, const DiffPair& pair) {
  std::string text = pair.name + ": " + pair.summary + " -- beyond tolerance\n";
  if (pair.side == DiffPair::Side::Both && !pair.result.size_mismatch) {
    if (pair.result.fraction > inputs.tolerance.max_fraction)
      text += "differing share " + number(pair.result.fraction) + " > max fraction " +
              number(inputs.tolerance.max_fraction) + "\n";
    if (inputs.tolerance.min_psnr_db && !(pair.result.psnr_db >= *inputs.tolerance.min_psnr_db))
      text += "PSNR below the minimum of " + number(*inputs.tolerance.min_psnr_db) + " dB\n";
  }
  if (pair.time_s) {
    char at[48];
    std::snprintf(at, sizeof at, "frame %ld at %.3f s\n", pair.frame, *pair.time_s);
    text += at;
  }
  text += "expected: " + inputs.expected + "\nactual: " + inputs.actual + "\n";
  text += "tolerance: " + tolerance_text(inputs.tolerance) + "\n";
  return text;
}

}  // namespace

std::string junit_xml(const DiffInputs& inputs, const std::vector<DiffPair>& pairs,
                      double seconds) {
  long failures = 0;
  for (const DiffPair& p : pairs) failures += p.beyond ? 1 : 0;
  const std::string counts = attribute("tests", std::to_string(pairs.size())) +
                             attribute("failures", std::to_string(failures)) +
                             attribute("errors", "0") + attribute("time", duration(seconds));

  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += "<testsuites" + attribute("name", "tumble diff") + counts + ">\n";
  xml += "  <testsuite" + attribute("name", "tumble diff") + counts + attribute("skipped", "0") +
         ">\n";
  xml += "    <properties>\n";
  const auto property = [&](const char* name, const std::string& value) {
    xml += "      <property" + attribute("name", name) + attribute("value", value) + "/>\n";
  };
  property("expected", inputs.expected);
  property("actual", inputs.actual);
  property("max_delta", std::to_string(inputs.tolerance.max_delta));
  property("max_fraction", number(inputs.tolerance.max_fraction));
  if (inputs.tolerance.min_psnr_db) property("min_psnr_db", number(*inputs.tolerance.min_psnr_db));
  xml += "    </properties>\n";
  for (const DiffPair& p : pairs) {
    // classname: the ACTUAL input, so that several diffs merged in one dashboard stay apart.
    xml += "    <testcase" + attribute("classname", inputs.actual) + attribute("name", p.name) +
           attribute("time", duration(p.seconds));
    if (!p.beyond) {
      xml += "/>\n";
      continue;
    }
    xml += ">\n      <failure" + attribute("type", "beyond tolerance") +
           attribute("message", p.summary + " -- beyond tolerance (" +
                                    tolerance_text(inputs.tolerance) + ")") +
           ">" + escape_markup_text(failure_details(inputs, p)) + "</failure>\n    </testcase>\n";
  }
  xml += "  </testsuite>\n</testsuites>\n";
  return xml;
}

}  // namespace tumble
