#include "tumble/junit_xml.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tumble {
namespace {

// The document is checked as text here (exact attributes, escaping); the e2e test parses a real
// one with an XML parser (tests/e2e/diff_report_check.py).

DiffPair passing(const std::string& name) {
  DiffPair p;
  p.name = name;
  p.result.total_pixels = 48;
  p.summary = "0 of 48 pixels differ (0%), largest delta 0, identical";
  return p;
}

DiffPair failing(const std::string& name) {
  DiffPair p;
  p.name = name;
  p.beyond = true;
  p.result.total_pixels = 48;
  p.result.differing_pixels = 6;
  p.result.fraction = 0.125;
  p.result.largest_delta = 40;
  p.result.psnr_db = 25.5;
  p.summary = "6 of 48 pixels differ (12.5%), largest delta 40, PSNR 25.50 dB";
  return p;
}

const DiffInputs kInputs{DiffInputs::Kind::Folders, "golden", "actual", {5, 0.001, {}}};

TEST(JunitXml, OneSuiteNamedTumbleDiffWithTheCounts) {
  const std::string xml = junit_xml(kInputs, {passing("a.png"), failing("b.png")}, 1.23456);
  EXPECT_TRUE(xml.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n")) << xml;
  EXPECT_NE(xml.find("<testsuite name=\"tumble diff\" tests=\"2\" failures=\"1\" errors=\"0\" "
                     "time=\"1.235\" skipped=\"0\">"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<testcase classname=\"actual\" name=\"a.png\" time=\"0.000\"/>"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<property name=\"max_delta\" value=\"5\"/>"), std::string::npos) << xml;
  EXPECT_EQ(xml.find("min_psnr_db"), std::string::npos) << "no --min-psnr, no property";
}

TEST(JunitXml, FailureMessageCarriesTheMetricsAndTolerance) {
  const std::string xml = junit_xml(kInputs, {failing("b.png")}, 0.0);
  EXPECT_NE(xml.find("<failure type=\"beyond tolerance\" message=\"6 of 48 pixels differ "
                     "(12.5%), largest delta 40, PSNR 25.50 dB -- beyond tolerance (max delta "
                     "5, max fraction 0.001)\">"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("differing share 0.125 &gt; max fraction 0.001\n"), std::string::npos) << xml;
}

TEST(JunitXml, NamesWithAnyCharactersAreEscaped) {
  const std::string xml =
      junit_xml(kInputs, {failing("a&b<c>\"q\"'s\x01.png"), passing("\xC3\xA9t\xC3\xA9.png")}, 0);
  EXPECT_NE(xml.find("name=\"a&amp;b&lt;c&gt;&quot;q&quot;&#39;s\xEF\xBF\xBD.png\""),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("a&amp;b&lt;c&gt;\"q\"'s\xEF\xBF\xBD.png: 6 of 48"), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"\xC3\xA9t\xC3\xA9.png\""), std::string::npos) << xml;
  EXPECT_EQ(xml.find('\x01'), std::string::npos);
}

TEST(JunitXml, AVideoFrameFailureSaysWhichFrameAndWhen) {
  DiffPair frame = failing("frame_00012");
  frame.frame = 12;
  frame.time_s = 0.2;
  const DiffInputs videos{DiffInputs::Kind::Videos, "a/clip.mp4", "b/clip.mp4", {}};
  const std::string xml = junit_xml(videos, {frame}, 0.0);
  EXPECT_NE(xml.find("name=\"frame_00012\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("frame 12 at 0.200 s\n"), std::string::npos) << xml;
}

}  // namespace
}  // namespace tumble
