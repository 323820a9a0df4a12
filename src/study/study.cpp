// run_study(): the runs, the reference, and what is derived from their comparison (trust, order
// fits, the Pareto front, the recommendation).
#include "tumble/study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "analytic_reference.hpp"
#include "order_fit.hpp"
#include "pareto.hpp"
#include "run_comparison.hpp"
#include "run_record.hpp"
#include "tumble/error.hpp"
#include "tumble/trajectory_writer.hpp"
#include "tumble/world_builder.hpp"
#include "work_pool.hpp"

namespace tumble::study {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The numeric reference is rk4 at the smallest studied step / 8, and its convergence check rk4 at
// twice that step. rk4 rather than adaptive at 1e-12: a fixed step halves cleanly, so the check
// estimates the reference's own error (≈ (2^p - 1) times it for order p >= 1, an upper bound).
// Adaptive would be ~10x cheaper, but its largest step must stay below the rest-speed limit
// (rest_speed_step_limit), where its error control never acts: tolerances 1e-12 and 3.2e-11 give
// bit-identical runs, and a check by tolerance would claim zero uncertainty (docs/accuracy.md).
constexpr double kReferenceRefinement = 8.0;
// A run whose first repetition took longer is timed once: its time is already well above the
// noise of a scheduler tick.
constexpr double kRepeatBelowS = 1.0;
constexpr int kRepetitions = 3;
// Reference runs longer than this many steps are refused: a typo in --dts, not a study.
constexpr double kMaxReferenceSteps = 1e9;

struct TaskResult {
  std::optional<RunRecord> record;
  std::string failure;
  double wall_s = 0.0;
};

std::string fmt(double x) {
  return format_double(x);
}

// The largest step at which the World's rest speed max(1 cm/s·√ℓ, 2 g dt) is still the small-dt
// limit for every body: a reference above it would stop bouncing earlier than the limit does.
double rest_speed_step_limit(const StudySetup& setup) {
  double limit = INFINITY;
  const double g = setup.def.gravity.norm();
  if (!setup.def.floor || g == 0.0) return limit;
  for (const ContactTolerances& t : setup.tolerances) {
    const double small_dt_rest =
        ContactTolerances::for_body(t.length_m, setup.def.gravity, 0.0).rest_speed_mps;
    limit = std::min(limit, small_dt_rest / (2.0 * g));
  }
  return limit;
}

TaskResult run_timed(const StudySetup& setup, const WorldDef& def, int repetitions,
                     const std::function<bool()>& stop) {
  TaskResult out;
  out.wall_s = INFINITY;
  for (int rep = 0; rep < repetitions; ++rep) {
    const auto start = Clock::now();
    try {
      RunRecord r = record_world(setup, def, stop);
      if (!out.record) out.record = std::move(r);  // every repetition computes the same
    } catch (const Error& e) {
      out.failure = e.what();
      out.record.reset();
      return out;
    }
    const double wall = seconds_since(start);
    out.wall_s = std::min(out.wall_s, wall);
    if (wall > kRepeatBelowS) break;
  }
  return out;
}

bool all_finite(const RunErrors& e, double drift) {
  return std::isfinite(e.position_m) && std::isfinite(e.orientation_rad) &&
         std::isfinite(e.pixel_px) && std::isfinite(drift);
}

std::string order_warning(const OrderFit& f, bool contacts, bool saturated) {
  std::string text = std::string(to_string(f.integrator)) + " converges at order " +
                     fmt(std::round(*f.order * 100.0) / 100.0) +
                     " on this scene, below its nominal " + std::to_string(f.nominal) + ". ";
  if (saturated)
    text +=
        "Its errors are as large as the bodies themselves at every step studied: the motion is "
        "wrong from the start (a flip out of phase, energy pumped in), so no order can show. "
        "Study smaller steps to see it converge.";
  else if (contacts)
    text +=
        "That is expected with floor contacts: an impact inside a step is located exactly, but "
        "the rest speed (2 g dt) and the impact's timing make errors near contacts fall like dt "
        "or dt², whatever the order between impacts. Judge it by the pixel error, not the order.";
  else
    text +=
        "Without contacts this usually means its errors reach the reference's uncertainty or the "
        "motion is sensitive to small changes (a tumbling box flips chaotically): check R² and "
        "the trusted column.";
  return text;
}

}  // namespace

std::vector<double> default_dts(double scene_dt_s) {
  return {4.0 * scene_dt_s, 2.0 * scene_dt_s, scene_dt_s, 0.5 * scene_dt_s, 0.25 * scene_dt_s};
}

std::string describe(const RunSetting& s) {
  if (s.tolerance) return std::string(to_string(s.integrator)) + " tol=" + fmt(*s.tolerance);
  return std::string(to_string(s.integrator)) + " dt=" + fmt(s.dt_s) + " s";
}

StudyResult run_study(const Scene& scene, const StudyPlan& plan, const StudyHooks& hooks) {
  const auto start = Clock::now();
  const StudySetup setup(scene);
  StudyResult result;
  result.scene_name = scene.source_name;
  result.scene_stem = scene.stem;
  result.duration_s = scene.simulation.duration_s;
  result.base_dt_s = scene.simulation.dt_s;
  result.fps = scene.render.fps;
  result.width = scene.render.width;
  result.height = scene.render.height;
  result.samples = setup.times.size();
  result.bodies = setup.bodies.size();
  result.jobs = plan.jobs;
  result.target_error_m = plan.target_error_m;

  // The rows: fixed-step integrators × dt in the plan's order, then adaptive × tolerance.
  bool adaptive = false;
  auto add_row = [&](const RunSetting& setting) {
    RunRow row;
    row.setting = setting;
    result.rows.push_back(row);
  };
  for (const Integrator i : plan.integrators) {
    if (i == Integrator::Adaptive) {
      adaptive = true;
      continue;
    }
    for (const double dt : plan.dts_s) add_row({i, dt, std::nullopt});
  }
  // adaptive: its dt is the largest step (max_step, default the frame interval the study samples
  // at); the scene's dt is only its first trial step, and the controller chooses the rest.
  const double adaptive_max_s = adaptive_max_step_s(scene.simulation, 1.0 / scene.render.fps);
  if (adaptive)
    for (const double tol : plan.tolerances) add_row({Integrator::Adaptive, adaptive_max_s, tol});

  // The reference: exact where the scene allows it, else rk4 much finer than any row.
  Reference& ref = result.reference;
  const std::optional<std::string> obstacle = analytic_obstacle(setup);
  ref.analytic = !obstacle;
  if (obstacle) {
    ref.why_numeric = *obstacle;
    double smallest = adaptive ? result.base_dt_s : INFINITY;
    for (const RunRow& row : result.rows) smallest = std::min(smallest, row.setting.dt_s);
    const double h = std::min(smallest / kReferenceRefinement, rest_speed_step_limit(setup));
    if (result.duration_s / h > kMaxReferenceSteps)
      throw Error(ErrorKind::BadInput, "the reference run (rk4 at dt = " + fmt(h) +
                                           " s) would take more than 1e9 " +
                                           "steps; study larger steps or a shorter --duration");
    ref.setting = {Integrator::Rk4, h, std::nullopt};
    ref.check = {Integrator::Rk4, 2.0 * h, std::nullopt};
  }

  // Tasks: [reference, check,] rows; the slowest first so the threads finish together.
  const std::size_t first_row = obstacle ? 2 : 0;
  const std::size_t tasks = first_row + result.rows.size();
  std::vector<TaskResult> done(tasks);
  auto setting_of = [&](std::size_t t) -> const RunSetting& {
    if (t < first_row) return t == 0 ? ref.setting : ref.check;
    return result.rows[t - first_row].setting;
  };
  auto expected_cost = [&](std::size_t t) {
    const RunSetting& s = setting_of(t);
    // Stages per step over the step: adaptive is guessed as rk4 at a quarter of its largest step.
    const double stages = s.tolerance                            ? 16.0
                          : s.integrator == Integrator::Rk4      ? 4.0
                          : s.integrator == Integrator::Midpoint ? 2.0
                                                                 : 1.0;
    return stages / s.dt_s * (t < first_row ? 1.0 : kRepetitions);
  };
  std::vector<std::size_t> order(tasks);
  for (std::size_t t = 0; t < tasks; ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return expected_cost(a) > expected_cost(b);
  });
  run_tasks(
      order, plan.jobs,
      [&](std::size_t t) {
        const RunSetting& s = setting_of(t);
        const WorldDef def = setup.def_for(s.integrator, s.dt_s, s.tolerance);
        done[t] = run_timed(setup, def, t < first_row ? 1 : kRepetitions, hooks.stop_requested);
      },
      [&](int n) {
        if (hooks.progress) hooks.progress(n, static_cast<int>(tasks));
      });

  // An unmatched bounce costs one frame in the bounce alignment: a bounce that would have to move
  // by more than about two frames to pair is called missed (and extra) rather than late.
  const double frame_s = 1.0 / result.fps;
  double largest_body_m = 0.0;
  for (const ContactTolerances& t : setup.tolerances)
    largest_body_m = std::max(largest_body_m, t.length_m);
  RunRecord reference;
  if (obstacle) {
    for (std::size_t t = 0; t < 2; ++t)
      if (!done[t].record)
        throw Error(ErrorKind::BadInput, "the reference run (" + describe(setting_of(t)) +
                                             ") failed: " + done[t].failure);
    reference = std::move(*done[0].record);
    const RunErrors check = compare_runs(*done[1].record, reference, frame_s);
    ref.uncertainty_m = check.position_m;
    ref.uncertainty_px = check.pixel_px;
    ref.uncertainty_rad = check.orientation_rad;
    ref.evaluations = reference.evaluations + done[1].record->evaluations;
    ref.wall_s = done[0].wall_s + done[1].wall_s;
    ref.diagnostics = reference.diagnostics;
  } else {
    AnalyticReference exact = analytic_reference(setup);
    reference = std::move(exact.record);
    ref.uncertainty_m = exact.uncertainty_m;
  }
  ref.energy_drift = energy_drift(reference, setup.energy_scale_J);
  for (std::size_t i = 0; i < setup.bodies.size(); ++i)
    for (const ImpactEvent& e : reference.events)
      if (e.body == static_cast<int>(i) && e.approach_speed_mps > reference.rest_speed_mps[i])
        ++ref.bounces;

  // Each row against the reference.
  for (std::size_t r = 0; r < result.rows.size(); ++r) {
    RunRow& row = result.rows[r];
    TaskResult& task = done[first_row + r];
    row.wall_s = task.wall_s;
    if (!task.record) {
      row.diverged = true;
      row.failure = task.failure;
      continue;
    }
    const RunRecord& run = *task.record;
    const RunErrors e = compare_runs(run, reference, frame_s);
    const double drift = energy_drift(run, setup.energy_scale_J);
    row.steps = run.steps;
    row.rejected_steps = run.rejected_steps;
    row.evaluations = run.evaluations;
    row.diagnostics = run.diagnostics;
    if (!all_finite(e, drift)) {
      row.diverged = true;
      row.failure = "its error against the reference overflowed";
      continue;
    }
    row.error_m = e.position_m;
    row.orientation_error_rad = e.orientation_rad;
    row.pixel_error_px = e.pixel_px;
    row.energy_drift = drift;
    row.bounces = e.bounces;
    row.missed_impacts = e.missed;
    row.extra_impacts = e.extra;
    row.impact_time_error_s = e.impact_time_s;
    row.trusted = row.error_m >= kTrustFactor * ref.uncertainty_m;
    row.indistinguishable = row.pixel_error_px + ref.uncertainty_px < kIndistinguishablePx;
  }

  // Pareto front by evaluations (deterministic; the wall-time front is only drawn).
  {
    std::vector<double> cost, error;
    std::vector<bool> valid;
    for (const RunRow& row : result.rows) {
      cost.push_back(static_cast<double>(row.evaluations));
      error.push_back(row.error_m);
      valid.push_back(!row.diverged);
    }
    const std::vector<bool> front = pareto_front(cost, error, valid);
    for (std::size_t r = 0; r < result.rows.size(); ++r) result.rows[r].pareto = front[r];
  }

  // Fitted orders of the fixed-step integrators, over their trusted rows.
  const bool contacts = !reference.events.empty();
  for (const Integrator i : plan.integrators) {
    if (i == Integrator::Adaptive) continue;
    OrderFit fit;
    fit.integrator = i;
    fit.nominal = order_of(i);
    std::vector<double> dts, errors;
    for (const RunRow& row : result.rows)
      if (row.setting.integrator == i && !row.diverged && row.trusted) {
        dts.push_back(row.setting.dt_s);
        errors.push_back(row.error_m);
      }
    fit.points = static_cast<int>(dts.size());
    if (const std::optional<LineFit> line = fit_order(dts, errors)) {
      fit.order = line->slope;
      fit.r_squared = line->r_squared;
      fit.below_nominal = line->slope < fit.nominal - 0.5;
      // Saturated: even the smallest error is a tenth of the largest body or more.
      const bool saturated =
          *std::min_element(errors.begin(), errors.end()) >= 0.1 * largest_body_m;
      if (fit.below_nominal) result.warnings.push_back(order_warning(fit, contacts, saturated));
    }
    result.fits.push_back(fit);
  }

  // The cheapest run that cannot be told from the reference, and the cheapest reaching a target.
  auto cheaper = [&](std::optional<std::size_t> best, std::size_t r) {
    if (!best) return true;
    const RunRow &a = result.rows[r], &b = result.rows[*best];
    return a.evaluations < b.evaluations ||
           (a.evaluations == b.evaluations && a.error_m < b.error_m);
  };
  for (std::size_t r = 0; r < result.rows.size(); ++r) {
    const RunRow& row = result.rows[r];
    if (row.diverged) continue;
    if (row.indistinguishable && cheaper(result.recommended, r)) result.recommended = r;
    if (plan.target_error_m && row.error_m + ref.uncertainty_m <= *plan.target_error_m &&
        cheaper(result.target, r))
      result.target = r;
  }
  if (!result.recommended && !result.rows.empty())
    result.warnings.push_back("no run is within " + fmt(kIndistinguishablePx) +
                              " px of the reference at " + std::to_string(result.width) + "x" +
                              std::to_string(result.height) +
                              "; study smaller steps (--dts) or tolerances (--tolerances)");
  if (ref.uncertainty_px >= 0.1 * kIndistinguishablePx)
    result.warnings.push_back("the reference itself is uncertain by " + fmt(ref.uncertainty_px) +
                              " px (" + fmt(ref.uncertainty_m) +
                              " m): the motion is sensitive to tiny changes; pixel errors below "
                              "that say little");
  if (!ref.diagnostics.empty()) {
    std::string codes;
    for (const std::string& c : ref.diagnostics) codes += (codes.empty() ? "" : ", ") + c;
    result.warnings.push_back("the reference run raised diagnostics (" + codes +
                              "); its numbers may be off");
  }
  result.wall_s = seconds_since(start);
  return result;
}

}  // namespace tumble::study
