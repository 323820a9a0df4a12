// study.md: what a person reads after a study — the reference and how sure it is, every row
// rounded, the fitted orders, warnings, the recommendation and the answer to --target-error.
#include <string>

#include "text_format.hpp"
#include "tumble/study.hpp"

namespace tumble::study {
namespace {

std::string notes(const StudyResult& result, std::size_t r) {
  const RunRow& row = result.rows[r];
  if (row.diverged) return "**diverged**: " + row.failure;
  std::string n;
  auto add = [&](const std::string& s) { n += (n.empty() ? "" : ", ") + s; };
  if (result.recommended == r) add("**recommended**");
  if (result.target == r) add("**cheapest to reach the target**");
  if (row.indistinguishable) add("indistinguishable");
  if (row.pareto) add("Pareto");
  if (!row.trusted) add("untrusted (near the reference's uncertainty)");
  for (const std::string& c : row.diagnostics) add("`" + c + "`");
  return n;
}

std::string reference_section(const StudyResult& result) {
  const Reference& ref = result.reference;
  std::string s = "## Reference\n\n";
  if (ref.analytic) {
    s += "**Exact**: every body is a particle or a box that does not turn, with no drag, so each "
         "follows parabolas between impacts at exact times (tumble's contact model: an impact "
         "faster than the rest speed leaves at e times its speed, a slower one stops the body; "
         "the rest speed is that of the small-dt limit, 1 cm/s at 1 m). Its uncertainty, " +
         rounded(ref.uncertainty_m) +
         " m, is round-off (1e-9 of the largest body) or, once a body comes to rest, its touch "
         "tolerance (1e-6 of its size): the model stops a slow body anywhere that close above "
         "the floor, depending on where the steps fall.\n";
  } else {
    s += "**Numeric**: " + short_setting(ref.setting) + ", checked against " +
         short_setting(ref.check) + ". The two differ by at most " + rounded(ref.uncertainty_m) +
         " m, " + rounded(ref.uncertainty_px) + " px and " + rounded(ref.uncertainty_rad) +
         " rad: the reference's uncertainty (an upper estimate: at order p the finer run is about "
         "2^p − 1 times closer to the limit than their difference). No exact reference: " +
         ref.why_numeric + ". The reference and its check took " + std::to_string(ref.evaluations) +
         " evaluations, " + milliseconds(ref.wall_s) + " ms.\n";
  }
  s += "\nThe reference has " + std::to_string(ref.bounces) +
       " bounces; its own energy drift over contact-free stretches is " +
       rounded(ref.energy_drift) + ".\n";
  return s;
}

}  // namespace

std::string study_markdown(const StudyResult& result) {
  std::string s = "# tumble study: " + result.scene_stem + "\n\n";
  s += "Scene `" + result.scene_name + "`: " + std::to_string(result.bodies) + " bod" +
       (result.bodies == 1 ? "y" : "ies") + ", " + rounded(result.duration_s, 6) + " s, base dt " +
       rounded(result.base_dt_s, 6) + " s. Every run is sampled at the " +
       std::to_string(result.fps) + " fps frame times and at the end (" +
       std::to_string(result.samples) + " samples); pixels are those of a " +
       std::to_string(result.width) + "x" + std::to_string(result.height) +
       " frame from the scene's camera. The " + std::to_string(result.rows.size()) +
       " runs and the reference took " + rounded(result.wall_s) + " s.\n\n";
  s += reference_section(result) + "\n";

  s += "## Runs\n\n";
  s += "| integrator | dt (s) | tolerance | steps | evaluations | wall (ms) | error (m) | pixel "
       "error (px) | orientation error (rad) | energy drift | bounce Δt (s) | missed / extra "
       "bounces | notes |\n";
  s += "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (std::size_t r = 0; r < result.rows.size(); ++r) {
    const RunRow& row = result.rows[r];
    const RunSetting& set = row.setting;
    s += "| " + std::string(to_string(set.integrator)) + " | " + rounded(set.dt_s, 4) + " | " +
         (set.tolerance ? rounded(*set.tolerance) : "") + " | ";
    if (row.diverged) {
      s += "| | | | | | | | | " + notes(result, r) + " |\n";
      continue;
    }
    s += std::to_string(row.steps) + " | " + std::to_string(row.evaluations) + " | " +
         milliseconds(row.wall_s) + " | " + rounded(row.error_m) + " | " +
         rounded(row.pixel_error_px) + " | " + rounded(row.orientation_error_rad) + " | " +
         rounded(row.energy_drift) + " | " +
         (row.impact_time_error_s ? rounded(*row.impact_time_error_s) : "") + " | " +
         std::to_string(row.missed_impacts) + " / " + std::to_string(row.extra_impacts) + " | " +
         notes(result, r) + " |\n";
  }

  s += "\n## Fitted convergence order\n\n";
  s += "Least-squares slope of log(error) against log(dt) over each integrator's trusted rows "
       "(error at least 10 times the reference's uncertainty).\n\n";
  s += "| integrator | nominal | fitted | R² | rows |\n|---|---:|---:|---:|---:|\n";
  for (const OrderFit& f : result.fits)
    s += "| " + std::string(to_string(f.integrator)) + " | " + std::to_string(f.nominal) + " | " +
         (f.order ? rounded(*f.order) : "—") + " | " + (f.order ? rounded(f.r_squared) : "—") +
         " | " + std::to_string(f.points) + " |\n";
  if (!result.warnings.empty()) {
    s += "\n";
    for (const std::string& w : result.warnings) s += "- **Warning**: " + w + "\n";
  }

  s += "\n## Recommendation\n\n";
  if (result.recommended) {
    const RunRow& row = result.rows[*result.recommended];
    s += "**" + short_setting(row.setting) + "**: the cheapest run (" +
         std::to_string(row.evaluations) + " derivative evaluations) within " +
         rounded(kIndistinguishablePx) + " px of the reference everywhere (" +
         rounded(row.pixel_error_px) + " px, " + rounded(row.error_m) +
         " m): its clip cannot be told from the reference's.\n";
  } else {
    s += "No run stays within " + rounded(kIndistinguishablePx) +
         " px of the reference; study smaller steps or tolerances.\n";
  }
  if (result.target_error_m) {
    s += "\nTarget error " + rounded(*result.target_error_m) + " m: ";
    if (result.target) {
      const RunRow& row = result.rows[*result.target];
      s += "**" + short_setting(row.setting) + "** is the cheapest run that reaches it (" +
           rounded(row.error_m) + " m, " + std::to_string(row.evaluations) + " evaluations).\n";
    } else {
      s += "no run reaches it; study smaller steps or tolerances.\n";
    }
  }

  s += "\n## Columns\n\n";
  s += "- error: the largest distance, over all samples and bodies, between a body point (box "
       "corners, a particle's centre) and the same point in the reference, metres.\n"
       "- pixel error: the same on screen, in pixels of the scene's camera at this size "
       "(camera.follow included); below " +
       rounded(kIndistinguishablePx) +
       " px (plus the reference's uncertainty) a run is indistinguishable.\n"
       "- orientation error: the largest rotation angle between a body's orientation and the "
       "reference's.\n"
       "- energy drift: the largest |E − E₀| / (K₀ + m g ℓ) over a contact-free stretch "
       "(consecutive samples with no impact between them and no vertex touching the floor), E₀ "
       "and K₀ the total and kinetic energy at the stretch's start, ℓ the body's size. Gravity "
       "conserves energy there; with drag the reference's own drift is the physics.\n"
       "- bounces: impacts faster than the rest speed of both runs, matched in order per body; "
       "Δt is the largest time difference of matched ones.\n"
       "- evaluations: derivative evaluations per body per stage, impact searches included (the "
       "work measure); wall: the best of 3 repetitions (a run over 1 s is timed once).\n";
  return s;
}

}  // namespace tumble::study
