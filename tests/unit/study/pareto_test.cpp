#include "../../../src/study/pareto.hpp"

#include <gtest/gtest.h>

namespace tumble::study {
namespace {

TEST(ParetoFront, KeepsOnlyRunsNothingBeatsOnBothCostAndError) {
  // (cost, error): b beats a on both; c is cheaper than b but worse; d costs more than c and is
  // no better; e is the most accurate; f is invalid (diverged) and would beat everything.
  const std::vector<double> cost = {10, 8, 4, 5, 100, 1};
  const std::vector<double> error = {1.0, 0.5, 2.0, 2.0, 1e-3, 1e-9};
  const std::vector<bool> valid = {true, true, true, true, true, false};
  const std::vector<bool> front = pareto_front(cost, error, valid);
  EXPECT_EQ(front, (std::vector<bool>{false, true, true, false, true, false}));
}

TEST(ParetoFront, EqualRunsAreBothOnIt) {
  const std::vector<bool> front = pareto_front({3, 3}, {1.0, 1.0}, {true, true});
  EXPECT_EQ(front, (std::vector<bool>{true, true}));
}

}  // namespace
}  // namespace tumble::study
