// The example scenes of bodies that meet (assets/scenes/dice.toml, stack.toml,
// newtons_cradle.toml) simulated through the CLI: what a user of each sees, in numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

struct Simulated {
  nlohmann::json report;
  Csv trajectory;
  std::string bytes;
};

Simulated simulate(const std::string& scene, const TestDir& dir, const std::string& out) {
  const RunResult r = run_tumble(
      {"simulate", (source_dir() / "assets/scenes" / scene).string(), "--out", out}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  Simulated s;
  s.report = read_json(dir / out / "run.json");
  s.bytes = read_file(dir / out / "trajectory.csv");
  s.trajectory = parse_csv(s.bytes);
  return s;
}

TEST(ContactScenes, FiveDiceThrownTogetherMeetLandAndRestDeterministically) {
  const TestDir dir;
  const Simulated a = simulate("dice.toml", dir, "a");
  const nlohmann::json& physics = a.report["physics"];
  // They meet each other, not only the floor: at least three die–die pairs touched.
  int die_pairs = 0;
  for (const nlohmann::json& p : physics["contact_pairs"]) {
    if (p["bodies"][0] != "floor") ++die_pairs;
    // No pair deeper than the touch tolerance of a 2 cm die (1e-6 ℓ = 2e-8 m), with 50 % for
    // the drift a resting contact may gather in one step before it is corrected.
    EXPECT_LT(p["deepest_penetration_m"].get<double>(), 3e-8) << p.dump();
  }
  EXPECT_GE(die_pairs, 3);
  EXPECT_GT(a.report["counts"]["impacts"].get<long>(), 5);
  // Energy never gained at an event beyond the potential energy of the touch tolerance
  // (5 dice · 9.6 g · g · 2e-8 m ≈ 1e-8 J); the throw's 81 mJ ends below 5 mJ (all at rest).
  EXPECT_LT(physics["max_contact_energy_gain_J"].get<double>(), 1e-8);
  EXPECT_LT(physics["energy_end_J"].get<double>(), physics["energy_start_J"].get<double>());
  // At rest by the end: the last sample of every die has no velocity.
  const std::size_t n = a.trajectory.rows.size();
  ASSERT_GE(n, 5u);
  for (std::size_t row = n - 5; row < n; ++row) {
    for (int c : {VX, VY, VZ, WX, WY, WZ}) EXPECT_EQ(a.trajectory.value(row, c), 0.0) << row;
    // Resting on a face: the centre half an edge above the floor.
    EXPECT_NEAR(a.trajectory.value(row, Y), 0.01, 1e-6) << row;
  }
  // The same scene, the same bytes.
  const Simulated b = simulate("dice.toml", dir, "b");
  EXPECT_EQ(a.bytes, b.bytes);
}

TEST(ContactScenes, TheTenBoxStackStaysWhereItIsPlaced) {
  const TestDir dir;
  const Simulated s = simulate("stack.toml", dir, "stack");
  // Every box at its placed height, to 1e-9 of its 0.2 m size, at the last sample.
  const std::size_t n = s.trajectory.rows.size();
  for (std::size_t row = n - 11; row < n; ++row) {
    const std::string body = s.trajectory.text(row, BODY);
    if (body == "ball") continue;
    const int k = std::stoi(body.substr(3));
    EXPECT_NEAR(s.trajectory.value(row, Y), 0.1 + 0.2 * k, 2e-10) << body;
    EXPECT_NEAR(s.trajectory.value(row, X), 0.0, 2e-10) << body;
  }
}

TEST(ContactScenes, NewtonsCradlePassesTheStrikeToTheLastBall) {
  const TestDir dir;
  const Simulated s = simulate("newtons_cradle.toml", dir, "cradle");
  // After the strike the last ball carries the striker's 0.5 m/s; the others are still.
  const std::size_t n = s.trajectory.rows.size();
  ASSERT_GE(n, 5u);
  for (std::size_t row = n - 5; row < n; ++row) {
    const double vx = s.trajectory.value(row, VX);
    if (row == n - 1)
      EXPECT_NEAR(vx, 0.5, 1e-6) << s.trajectory.text(row, BODY);
    else
      EXPECT_LT(std::abs(vx), 5e-7) << s.trajectory.text(row, BODY);
  }
}

}  // namespace
}  // namespace tumble_e2e
