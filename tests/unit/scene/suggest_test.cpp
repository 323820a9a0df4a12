#include <gtest/gtest.h>

#include "tumble/scene.hpp"

namespace tumble {
namespace {

const std::vector<std::string_view> kBodyKeys = {
    "name", "shape", "size", "mass", "density", "velocity", "restitution", "position", "color"};

TEST(ClosestMatch, FindsATypo) {
  EXPECT_EQ(closest_match("restitusion", kBodyKeys), "restitution");  // one substitution
  EXPECT_EQ(closest_match("mas", kBodyKeys), "mass");                 // one deletion
  EXPECT_EQ(closest_match("colour", kBodyKeys), "color");             // one insertion
}

TEST(ClosestMatch, CountsASwapOfNeighboursAsOneEdit) {
  // "szie" is 2 Levenshtein edits from "size" but one transposition; 4 / 3 allows only 1.
  EXPECT_EQ(closest_match("szie", kBodyKeys), "size");
}

TEST(ClosestMatch, IgnoresCase) {
  EXPECT_EQ(closest_match("MASS", kBodyKeys), "mass");
  EXPECT_EQ(closest_match("Velocty", kBodyKeys), "velocity");
}

TEST(ClosestMatch, ReturnsNothingWhenNothingIsClose) {
  EXPECT_EQ(closest_match("friction", kBodyKeys), std::nullopt);
  EXPECT_EQ(closest_match("zzzz", kBodyKeys), std::nullopt);
  EXPECT_EQ(closest_match("mass", {}), std::nullopt);
}

TEST(ClosestMatch, AllowsAboutOneEditInThree) {
  // 11 letters allow 3 edits, 4 letters only 1.
  EXPECT_EQ(closest_match("restetusion", kBodyKeys), "restitution");  // 2 edits
  EXPECT_EQ(closest_match("rastetusion", kBodyKeys), "restitution");  // 3 edits
  EXPECT_EQ(closest_match("rastetusiom", kBodyKeys), std::nullopt);   // 4 edits
  EXPECT_EQ(closest_match("maxx", kBodyKeys), std::nullopt);          // 2 edits from "mass"
}

TEST(ClosestMatch, BreaksTiesByCandidateOrder) {
  // "cat" is one edit from both "bat" and "car": the first listed wins, whichever it is.
  EXPECT_EQ(closest_match("cat", {"bat", "car"}), "bat");
  EXPECT_EQ(closest_match("cat", {"car", "bat"}), "car");
}

TEST(ClosestMatch, PrefersTheNearerCandidateOverAnEarlierOne) {
  // "midpont" is 2 edits from "midpoints" (within its limit of 7 / 3) and 1 from "midpoint".
  EXPECT_EQ(closest_match("midpont", {"midpoints", "midpoint"}), "midpoint");
}

}  // namespace
}  // namespace tumble
