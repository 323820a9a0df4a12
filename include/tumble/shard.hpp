#pragma once
/// Which of a sweep's jobs one process runs: shard I of N runs the jobs j with j mod N = I, so
/// shards interleave (each gets a like mix of the plan) and together cover every job once.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace tumble::sweep {

struct Shard {
  std::size_t index = 0;  ///< I, in [0, count)
  std::size_t count = 1;  ///< N >= 1
  bool contains(std::size_t job) const { return job % count == index; }
  std::string describe() const { return std::to_string(index) + "/" + std::to_string(count); }
};

/// "I/N" as `--shard` gives it. Throws tumble::Error (BadInput) unless 0 <= I < N.
Shard parse_shard(std::string_view text);

/// Reads an environment variable: its value, or nullopt when unset.
using Environment = std::function<std::optional<std::string>(const char* name)>;

/// The shard a scheduler gives this process, or nullopt outside one: in a Slurm array task,
/// (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN) / SLURM_ARRAY_TASK_STEP (step 1 when unset) of
/// SLURM_ARRAY_TASK_COUNT; in a Kubernetes Indexed Job, JOB_COMPLETION_INDEX of `shards`
/// (--shards N, the Job's completions; required there). Throws tumble::Error (BadInput) for a
/// value that is not a number or a shard out of range.
std::optional<Shard> shard_from_environment(const Environment& env,
                                            std::optional<std::size_t> shards);

}  // namespace tumble::sweep
