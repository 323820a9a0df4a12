#pragma once
/// A sweep job's effective scene: the plan's base scene with the job's parameters set, written as
/// a standalone scene file (relative mesh paths made absolute, resolved against the base scene's
/// folder, so the file is valid wherever it lies). Its first lines are comments naming the job,
/// the command and its options, and the parameters: its SHA-256, which run.json records, then
/// changes whenever anything that decides the job's outputs changes.

#include <functional>
#include <string>

#include "tumble/sweep.hpp"

namespace tumble::sweep {

/// The effective scene text of `job`. Throws tumble::Error (BadInput) at the plan's key when a
/// key path runs through something that is not a table in the scene.
std::string job_scene_text(const Plan& plan, const Job& job);

/// Loads and checks a scene's text the way the job will (the scene loader, the command's
/// overrides); `name` is the file name its errors carry. Throws tumble::Error.
using SceneCheck = std::function<void(const std::string& text, const std::string& name)>;

/// Checks `job`'s effective scene with `check`. An error the scene loader finds is reported at
/// the plan's place that caused it: the grid value or distribution when the scene rejects the
/// value, the key path when it rejects the key (unknown key, with the loader's suggestion),
/// `args` when the command's options do not fit the scene; the message names the job.
void check_job_scene(const Plan& plan, const Job& job, const SceneCheck& check);

/// A cheap check of the plan itself, whatever shard runs: each random key at the ends of its
/// range (uniform, integer: both ends; choice: every value; normal: none) with the other keys as
/// job 0 has them; then job 0, and for each grid value the first job that has it. About as many
/// checks as the plan has values, whatever its job count. Errors as check_job_scene's.
void check_plan_values(const Plan& plan, const SceneCheck& check);

}  // namespace tumble::sweep
