#pragma once
/// `tumble study`: the speed/accuracy trade of one scene. Every fixed-step integrator runs at
/// every step size and `adaptive` at every tolerance; each run is sampled at the frame times and
/// at the end, and measured against a reference run: an exact one (closed-form parabolas and
/// impacts) where the scene allows it, else a much finer rk4 run whose own convergence is checked.
/// The results are plain data; study_csv(), study_markdown() and study_svg() turn them into the
/// three outputs, write_study() writes them atomically.
///
/// Runs are independent World values, spread over `jobs` threads: every result except the wall
/// times (and what is derived from them) is the same for any number of jobs.

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tumble/integrators.hpp"
#include "tumble/scene.hpp"

namespace tumble::study {

/// Default adaptive tolerances (SPEC: 1e-4 … 1e-10).
inline constexpr std::array<double, 4> kDefaultTolerances = {1e-4, 1e-6, 1e-8, 1e-10};
/// Range of tolerances a study accepts: below 1e-14 the local error is round-off.
inline constexpr double kMinTolerance = 1e-14, kMaxTolerance = 0.1;
/// A run whose largest on-screen deviation from the reference is below this many pixels cannot
/// be told from it in the clip (half a pixel: below the anti-aliased edge's own blur).
inline constexpr double kIndistinguishablePx = 0.5;
/// A row is trusted when its error is at least this many times the reference's uncertainty.
inline constexpr double kTrustFactor = 10.0;

/// The scene's dt × 4, 2, 1, 1/2, 1/4: the default fixed steps.
std::vector<double> default_dts(double scene_dt_s);

/// What a study runs.
struct StudyPlan {
  std::vector<Integrator> integrators;  ///< in this order; Adaptive runs once per tolerance
  std::vector<double> dts_s;            ///< every fixed-step integrator runs at each of these
  std::vector<double> tolerances;       ///< adaptive runs: the scene's dt first, max_step largest
  std::optional<double> target_error_m;  ///< also find the cheapest run reaching this error
  int jobs = 1;                          ///< threads
};

/// Caller hooks. `stop_requested` is polled from the worker threads (it must be thread-safe);
/// `progress` is called on the calling thread with the runs done so far.
struct StudyHooks {
  std::function<bool()> stop_requested;
  std::function<void(int done, int total)> progress;
};

/// Thrown by run_study() when stop_requested() turned true: nothing is returned or written.
struct Cancelled {};

/// One setting of the study: a fixed-step integrator at dt, or adaptive at a tolerance with dt
/// as its largest step (the scene's max_step; the scene's dt is its first trial step).
struct RunSetting {
  Integrator integrator = Integrator::Rk4;
  double dt_s = 0.001;
  std::optional<double> tolerance;  ///< adaptive only
};

/// "rk4 dt=0.001 s", "adaptive tol=1e-08".
std::string describe(const RunSetting& setting);

/// One row of the study: what a run cost and how far it is from the reference.
struct RunRow {
  RunSetting setting;
  bool diverged = false;    ///< the state stopped being finite (its numbers are then meaningless)
  std::string failure;      ///< why, for a diverged run
  long steps = 0;           ///< fixed steps taken, or accepted adaptive substeps
  long rejected_steps = 0;  ///< adaptive: rejected substeps
  long evaluations = 0;     ///< derivative evaluations (per body per stage, impact searches too)
  double wall_s = 0.0;      ///< best of up to 3 repetitions
  double error_m = 0.0;     ///< largest distance of a body point from the reference's
  double orientation_error_rad = 0.0;  ///< largest geodesic angle from the reference's
  double pixel_error_px = 0.0;         ///< largest on-screen distance from the reference's
  double energy_drift = 0.0;  ///< largest relative energy change over contact-free stretches
  int bounces = 0;  ///< bounces compared (above both runs' rest speeds), reference's count
  int missed_impacts = 0, extra_impacts = 0;  ///< bounces of the reference missing here, and extra
  std::optional<double> impact_time_error_s;  ///< largest |Δt| of matched bounces
  bool trusted = false;            ///< error >= kTrustFactor × the reference's uncertainty
  bool indistinguishable = false;  ///< pixel error (+ reference's) below kIndistinguishablePx
  bool pareto = false;             ///< no other run has both fewer evaluations and a smaller error
  std::vector<std::string> diagnostics;  ///< World diagnostic codes the run raised
};

/// The reference every run is measured against.
struct Reference {
  bool analytic = false;
  std::string why_numeric;    ///< what rules the exact solution out (numeric only)
  RunSetting setting, check;  ///< numeric: the reference run and its convergence check
  /// How far the reference itself may be off: numeric, its distance from the check run (an upper
  /// estimate when it converges at order >= 1); analytic, a round-off floor.
  double uncertainty_m = 0.0, uncertainty_px = 0.0, uncertainty_rad = 0.0;
  double energy_drift = 0.0;  ///< its own, for comparison (with drag this is physics)
  int bounces = 0;            ///< its bounces, every body
  long evaluations = 0;       ///< of the reference run and its check
  double wall_s = 0.0;
  std::vector<std::string> diagnostics;
};

/// Least-squares slope of log(error) against log(dt) over an integrator's trusted rows.
struct OrderFit {
  Integrator integrator = Integrator::Euler;
  int nominal = 1;
  int points = 0;               ///< rows used
  std::optional<double> order;  ///< none with fewer than 2 rows
  double r_squared = 0.0;
  bool below_nominal = false;  ///< order < nominal - 0.5
};

struct StudyResult {
  std::string scene_name;  ///< as given, or "<default>"
  std::string scene_stem;
  double duration_s = 0.0, base_dt_s = 0.0;
  int fps = 60, width = 1280, height = 720;
  std::size_t samples = 0, bodies = 0;
  int jobs = 1;
  Reference reference;
  std::vector<RunRow>
      rows;  ///< fixed-step integrator × dt in plan order, then adaptive × tolerance
  std::vector<OrderFit> fits;
  std::optional<std::size_t> recommended;  ///< cheapest indistinguishable row
  std::optional<double> target_error_m;
  std::optional<std::size_t> target;  ///< cheapest row with error (+ uncertainty) <= target
  std::vector<std::string> warnings;  ///< for study.md and stderr
  double wall_s = 0.0;                ///< the whole study
};

/// Runs the study. Throws tumble::Error (BadInput) when the reference run fails, Cancelled when
/// stopped. Runs that diverge are rows, not failures.
StudyResult run_study(const Scene& scene, const StudyPlan& plan, const StudyHooks& hooks = {});

/// study.csv: a header starting `integrator,dt,tolerance,steps,evaluations,wall_s,error,
/// pixel_error,energy_drift`, then one line per row; numbers in their shortest exact form.
std::string study_csv(const StudyResult& result);
/// The column names of study.csv, in order.
const std::vector<std::string>& study_csv_columns();
/// study.md: the rows for a person, the reference, the fitted orders, the recommendation.
std::string study_markdown(const StudyResult& result);
/// study.svg: log-log work-precision plot (error against evaluations, and against wall time).
std::string study_svg(const StudyResult& result);
/// The compact table and recommendation printed on stdout.
std::string study_summary(const StudyResult& result);

/// Writes study.csv, study.md and study.svg into `dir`, each atomically; returns their paths.
std::vector<std::filesystem::path> write_study(const std::filesystem::path& dir,
                                               const StudyResult& result);

}  // namespace tumble::study
