// Fitted convergence orders: the line fit itself, and the orders a study measures on a scene
// without contacts, where every integrator must show its nominal order.
#include "../../../src/study/order_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tumble/study.hpp"

namespace tumble::study {
namespace {

TEST(LineFit, RecoversAnExactLine) {
  const std::optional<LineFit> f = fit_line({0, 1, 2, 3}, {1, 3, 5, 7});
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->slope, 2.0, 1e-14);
  EXPECT_NEAR(f->intercept, 1.0, 1e-14);
  EXPECT_NEAR(f->r_squared, 1.0, 1e-14);
  EXPECT_FALSE(fit_line({1}, {1}).has_value());
  EXPECT_FALSE(fit_line({2, 2}, {1, 3}).has_value());
}

TEST(LineFit, RSquaredFallsWithScatter) {
  const std::optional<LineFit> f = fit_line({0, 1, 2, 3}, {0, 2, 1, 3});
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->slope, 0.8, 1e-14);
  EXPECT_LT(f->r_squared, 0.7);
}

TEST(OrderFit, PowerLawGivesItsExponent) {
  // error = 3 dt^4 exactly: slope 4 on log-log axes; non-positive errors are left out.
  const std::vector<double> dts = {0.04, 0.02, 0.01, 0.005};
  std::vector<double> errors;
  for (const double dt : dts) errors.push_back(3.0 * std::pow(dt, 4));
  errors.push_back(0.0);
  std::vector<double> dts_with_zero = dts;
  dts_with_zero.push_back(0.001);
  const std::optional<LineFit> f = fit_order(dts_with_zero, errors);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->slope, 4.0, 1e-12);
}

// The torque-free tumble of docs/physics.md (box 1×2×3, ω = (1, 0.7, 1.3)), no floor, no gravity:
// no contact to spoil the orders, so the study must measure each integrator's own. Steps where
// all three are in their asymptotic range and well above the reference's round-off.
TEST(OrderFit, StudyMeasuresNominalOrdersOnATorqueFreeTumble) {
  const Scene scene = parse_scene(R"([simulation]
duration = 1.0
gravity = [0.0, 0.0, 0.0]
[[body]]
name = "box"
shape = "box"
size = [1.0, 2.0, 3.0]
mass = 1.0
angular_velocity = [1.0, 0.7, 1.3]
)",
                                  "torque_free.toml");
  StudyPlan plan;
  plan.integrators = {Integrator::Euler, Integrator::Midpoint, Integrator::Rk4};
  plan.dts_s = {0.02, 0.01, 0.005, 0.0025};
  plan.jobs = 2;
  const StudyResult result = run_study(scene, plan);
  ASSERT_EQ(result.fits.size(), 3u);
  EXPECT_FALSE(result.reference.analytic);
  // ±0.2 as in the simulation's own order tests; the fit spans a factor 8 in dt.
  const double expected[] = {1.0, 2.0, 4.0};
  for (std::size_t i = 0; i < 3; ++i) {
    const OrderFit& f = result.fits[i];
    ASSERT_TRUE(f.order.has_value()) << to_string(f.integrator);
    EXPECT_EQ(f.points, 4) << to_string(f.integrator);
    EXPECT_NEAR(*f.order, expected[i], 0.2) << to_string(f.integrator);
    EXPECT_GT(f.r_squared, 0.99) << to_string(f.integrator);
    EXPECT_FALSE(f.below_nominal);
  }
  EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
}

}  // namespace
}  // namespace tumble::study
