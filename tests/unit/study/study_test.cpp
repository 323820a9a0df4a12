// run_study() as a whole: the rows it makes, diverged runs as rows, results independent of the
// number of threads, the recommendation and the target, and the CSV they are written as.
#include "tumble/study.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "../../../src/study/run_record.hpp"

namespace tumble::study {
namespace {

// A short version of the built-in scene: the seed's tilted, spinning box dropped on a floor.
Scene short_drop() {
  Scene s = default_scene();
  s.simulation.duration_s = 1.0;
  s.render.width = 320;
  s.render.height = 180;
  return s;
}

StudyPlan full_plan(const Scene& s, int jobs) {
  StudyPlan plan;
  plan.integrators = {Integrator::Euler, Integrator::SymplecticEuler, Integrator::Midpoint,
                      Integrator::Rk4, Integrator::Adaptive};
  plan.dts_s = default_dts(s.simulation.dt_s);
  plan.tolerances.assign(kDefaultTolerances.begin(), kDefaultTolerances.end());
  plan.target_error_m = 1e-3;
  plan.jobs = jobs;
  return plan;
}

// The full default study of the short drop on 1 and on 3 threads, computed once for the tests
// below (the sanitizer build runs them too).
const StudyResult& shared_study(int jobs) {
  static const StudyResult one = run_study(short_drop(), full_plan(short_drop(), 1));
  static const StudyResult three = run_study(short_drop(), full_plan(short_drop(), 3));
  return jobs == 1 ? one : three;
}

std::vector<std::vector<std::string>> csv_cells(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::size_t begin = 0;
    for (std::size_t comma; (comma = line.find(',', begin)) != std::string::npos; begin = comma + 1)
      cells.push_back(line.substr(begin, comma - begin));
    cells.push_back(line.substr(begin));
    rows.push_back(cells);
  }
  return rows;
}

TEST(SampleTimes, FrameTimesThenTheEnd) {
  const std::vector<double> t = sample_times(1.0, 60);
  ASSERT_EQ(t.size(), 61u);  // k/60 for k = 0 … 59, then t = 1
  EXPECT_EQ(t[0], 0.0);
  EXPECT_EQ(t[59], 59.0 / 60.0);
  EXPECT_EQ(t[60], 1.0);
  // round(1.01·60) = 61 frames, the last at 1 s; the end follows.
  EXPECT_EQ(sample_times(1.01, 60).size(), 62u);
}

TEST(Study, OneRowPerSettingAndTheSameResultsOnAnyNumberOfThreads) {
  const Scene s = short_drop();
  const StudyResult& one = shared_study(1);
  const StudyResult& three = shared_study(3);
  ASSERT_EQ(one.rows.size(), 4u * 5u + 4u);
  EXPECT_EQ(one.rows[0].setting.integrator, Integrator::Euler);
  EXPECT_EQ(one.rows[0].setting.dt_s, 4.0 * s.simulation.dt_s);
  EXPECT_EQ(one.rows[20].setting.integrator, Integrator::Adaptive);
  // The largest step: max_step, by default the frame interval the study samples at.
  EXPECT_EQ(one.rows[20].setting.dt_s, 1.0 / s.render.fps);
  EXPECT_EQ(*one.rows[23].setting.tolerance, 1e-10);

  // Everything but wall_s (column 6) is identical.
  auto without_wall = [](const StudyResult& r) {
    std::vector<std::vector<std::string>> cells = csv_cells(study_csv(r));
    for (auto& row : cells) row.erase(row.begin() + 5);
    return cells;
  };
  EXPECT_EQ(without_wall(one), without_wall(three));
  EXPECT_EQ(study_svg(one).substr(0, 5), "<svg ");
}

TEST(Study, RecommendsTheCheapestIndistinguishableRun) {
  const StudyResult& r = shared_study(1);
  ASSERT_TRUE(r.recommended.has_value());
  const RunRow& best = r.rows[*r.recommended];
  EXPECT_TRUE(best.indistinguishable);
  EXPECT_LT(best.pixel_error_px, kIndistinguishablePx);
  for (const RunRow& row : r.rows)
    if (!row.diverged && row.indistinguishable) {
      EXPECT_GE(row.evaluations, best.evaluations);
    }
  // Euler at 4 dt is visibly off (tens of pixels at this size), so not every run qualifies.
  EXPECT_FALSE(r.rows[0].indistinguishable);
}

TEST(Study, TargetErrorNamesTheCheapestRunReachingIt) {
  const StudyResult& r = shared_study(1);
  ASSERT_TRUE(r.target.has_value());
  const RunRow& t = r.rows[*r.target];
  EXPECT_LE(t.error_m + r.reference.uncertainty_m, 1e-3);
  for (const RunRow& row : r.rows)
    if (!row.diverged && row.error_m + r.reference.uncertainty_m <= 1e-3) {
      EXPECT_GE(row.evaluations, t.evaluations);
    }
  EXPECT_NE(study_markdown(r).find("Target error 0.001 m"), std::string::npos);
}

TEST(Study, ADivergedRunIsARowWithEmptyNumbers) {
  // Stiff drag (c/m = 1e4 /s): explicit Euler at dt = 0.01 multiplies the velocity by -99 each
  // step and overflows; at dt = 1e-4 it is stable. The reference runs at 1e-4 / 8.
  const Scene s = parse_scene(R"([simulation]
duration = 2.0
linear_drag = 10000.0
[[body]]
name = "ball"
shape = "particle"
mass = 1.0
velocity = [1.0, 0.0, 0.0]
)",
                              "stiff.toml");
  StudyPlan plan;
  plan.integrators = {Integrator::Euler};
  plan.dts_s = {0.01, 1e-4};
  const StudyResult r = run_study(s, plan);
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_TRUE(r.rows[0].diverged);
  EXPECT_NE(r.rows[0].failure.find("stopped being finite"), std::string::npos);
  EXPECT_FALSE(r.rows[1].diverged);
  const auto cells = csv_cells(study_csv(r));
  ASSERT_EQ(cells.size(), 3u);
  const std::vector<std::string>& columns = study_csv_columns();
  ASSERT_EQ(cells[1].size(), columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const std::string& v = cells[1][c];
    const std::string& name = columns[c];
    const bool flag = name == "trusted" || name == "indistinguishable" || name == "pareto";
    const std::string expected = name == "integrator" ? "euler"
                                 : name == "dt"       ? "0.01"
                                 : name == "status"   ? "diverged"
                                 : flag               ? "false"
                                                      : "";
    EXPECT_EQ(v, expected) << name;
  }
  EXPECT_EQ(cells[2][columns.size() - 5], "ok");
}

TEST(Study, AdaptiveRowsDifferByToleranceOnATorqueFreeBox) {
  // A box tumbling fast (18 rad/s) about no principal axis in zero gravity: nothing but the
  // integrator's error sets the steps (measured: 1 572, 2 292 and 5 496 evaluations). With dt the
  // first trial step and max_step the frame interval, the controller chooses: the looser the
  // tolerance, the larger its steps and the fewer evaluations (about tol^(-1/5) each: 2.5x per two
  // decades).
  const Scene s = parse_scene(R"([simulation]
duration = 2.0
gravity = [0.0, 0.0, 0.0]
integrator = "adaptive"
[render]
width = 320
height = 180
[camera]
position = [4.0, 3.0, 5.0]
target = [0.0, 0.0, 0.0]
[[body]]
name = "box"
shape = "box"
size = [1.0, 2.0, 3.0]
mass = 3.0
orientation = { axis = [1.0, 2.0, 0.5], degrees = 23.0 }
angular_velocity = [10.0, 7.0, 13.0]
)",
                              "torque_free.toml");
  StudyPlan plan;
  plan.integrators = {Integrator::Adaptive};
  plan.tolerances = {1e-6, 1e-8, 1e-10};
  const StudyResult r = run_study(s, plan);
  ASSERT_EQ(r.rows.size(), 3u);
  for (const RunRow& row : r.rows) {
    EXPECT_FALSE(row.diverged);
    EXPECT_EQ(row.setting.dt_s, 1.0 / 60.0);  // the largest step: the frame interval
  }
  EXPECT_LT(r.rows[0].evaluations, r.rows[1].evaluations);
  EXPECT_LT(r.rows[1].evaluations, r.rows[2].evaluations);
  // And what the evaluations buy: a smaller error at a tighter tolerance.
  EXPECT_GT(r.rows[0].error_m, r.rows[2].error_m);
  // Cheaper than the old fixed cap (7 evaluations per 1 ms step: 14 000) at every tolerance.
  EXPECT_LT(r.rows[2].evaluations, 14000);
  // An explicit max_step caps the steps: at 1 ms every tolerance takes the same 2 000 steps.
  Scene capped = s;
  capped.simulation.max_step_s = 0.001;
  const StudyResult c = run_study(capped, plan);
  ASSERT_EQ(c.rows.size(), 3u);
  EXPECT_EQ(c.rows[0].setting.dt_s, 0.001);
  EXPECT_EQ(c.rows[0].evaluations, c.rows[1].evaluations);
}

TEST(StudyCsv, HeaderStartsWithTheSpecColumns) {
  const std::string csv = study_csv(StudyResult{});
  EXPECT_EQ(csv.rfind("integrator,dt,tolerance,steps,evaluations,wall_s,error,pixel_error,"
                      "energy_drift,",
                      0),
            0u);
}

}  // namespace
}  // namespace tumble::study
