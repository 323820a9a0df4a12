#pragma once
/// A sweep plan (`tumble sweep PLAN.toml`): a base scene, the command every job runs with its
/// options, a [grid] of values and/or a [random] block. Job i's parameters are a pure function of
/// the plan and i, so shards share nothing and any job can be rerun alone. The plan is parsed and
/// checked here with every error pointing at its place in the plan (file:line:column); checking
/// each job's scene through the scene loader is job_scene.hpp's part. Format: docs/sweeps.md.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/error.hpp"

namespace tumble::sweep {

/// A random draw for one key path. Scalars: `uniform = [a, b]`, `normal = [mean, sd]`,
/// `integer = [a, b]` (inclusive); vectors: `uniform`/`normal` of two equal-length arrays, one
/// component drawn after the other; `choice = [v1, v2, ...]`: any values, each equally likely.
struct Distribution {
  enum class Kind { Uniform, Normal, Integer, Choice };
  Kind kind = Kind::Uniform;
  std::vector<double> first, second;  ///< per component: [a, b] or [mean, sd]
  bool vector = false;                ///< drawn as an array (even of one component)
  std::int64_t lo = 0, hi = 0;        ///< integer
  std::vector<std::string> choices;   ///< choice: each value as TOML text
};

/// A key path of the plan with where its key and value are written.
struct PlanKey {
  std::string path;         ///< "floor.restitution", "body.box.orientation.degrees"
  SourceLocation key_at;    ///< the key in the plan
  SourceLocation value_at;  ///< its value (the grid's array, the distribution's table)
};

/// A [grid] entry: the values it takes, in order, each as TOML text.
struct GridAxis {
  PlanKey key;
  std::vector<std::string> values;
  std::vector<SourceLocation> value_at;  ///< each value's place in the plan
};

/// A [random] entry.
struct RandomKey {
  PlanKey key;
  Distribution distribution;
};

struct Plan {
  std::string path;                  ///< the plan file as given
  std::string stem;                  ///< its stem: the default output folder out/<stem>/
  std::filesystem::path scene_path;  ///< the base scene, resolved against the plan's folder
  SourceLocation scene_at;
  std::string scene_text;  ///< the base scene's bytes
  std::string command;     ///< "render" or "simulate"
  SourceLocation command_at;
  std::vector<std::string> args;  ///< options for every job, as a command line gives them
  SourceLocation args_at;
  std::vector<GridAxis> grid;  ///< in the plan's order: the first varies slowest
  std::optional<std::size_t> random_count;
  std::uint64_t seed = 0;
  std::vector<RandomKey> random;  ///< in the plan's order: key index = place here
  SourceLocation random_at;

  /// The number of jobs: product of the grid's sizes (1 without a grid) times count (1 without
  /// [random]).
  std::size_t job_count() const;
  /// Every key path the jobs set, grid first then random, each in the plan's order.
  std::vector<const PlanKey*> keys() const;
};

/// Parses and checks plan text (but not the scenes: see check_job_scene). `path` names the plan
/// in errors and resolves the scene path; the base scene is read. Throws tumble::Error
/// (BadInput) with file:line:column.
Plan parse_plan(std::string_view text, const std::string& path);
/// Reads and parses a plan file; a file that cannot be read is BadInput.
Plan load_plan(const std::filesystem::path& path);

/// One value a job gives a key path.
struct Parameter {
  const PlanKey* key = nullptr;
  std::string value;    ///< TOML text: 0.2, [0.0, 0.0, 1.0], "fxaa"
  SourceLocation from;  ///< the grid value or the distribution it came from
};

struct Job {
  std::size_t index = 0;
  std::vector<Parameter> parameters;  ///< in keys() order
};

/// Job `index` (< plan.job_count()): grid point index / count (the first axis slowest), random
/// draw from SplitMix64::stream(seed, index, key index) for each random key in turn.
Job make_job(const Plan& plan, std::size_t index);

/// "job_00042": the folder of job `index` under the sweep's output folder.
std::string job_folder_name(std::size_t index);

}  // namespace tumble::sweep
