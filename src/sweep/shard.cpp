#include "tumble/shard.hpp"

#include <charconv>

#include "tumble/error.hpp"

namespace tumble::sweep {
namespace {

[[noreturn]] void bad(const std::string& message) {
  throw Error(ErrorKind::BadInput, message);
}

std::optional<long long> whole_number(std::string_view text) {
  long long value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

Shard checked(long long index, long long count, const std::string& source) {
  if (count < 1) bad(source + ": the number of shards must be >= 1, got " + std::to_string(count));
  if (index < 0 || index >= count)
    bad(source + ": shard " + std::to_string(index) + " is out of range [0, " +
        std::to_string(count - 1) + "]");
  return {static_cast<std::size_t>(index), static_cast<std::size_t>(count)};
}

}  // namespace

Shard parse_shard(std::string_view text) {
  const std::size_t slash = text.find('/');
  const auto index = slash == text.npos ? std::nullopt : whole_number(text.substr(0, slash));
  const auto count = slash == text.npos ? std::nullopt : whole_number(text.substr(slash + 1));
  if (!index || !count)
    bad("--shard must look like 0/4 (this shard / number of shards), not \"" + std::string(text) +
        "\"");
  return checked(*index, *count, "--shard " + std::string(text));
}

std::optional<Shard> shard_from_environment(const Environment& env,
                                            std::optional<std::size_t> shards) {
  const auto number = [&](const char* name, long long fallback) -> long long {
    const std::optional<std::string> value = env(name);
    if (!value) return fallback;
    const auto n = whole_number(*value);
    if (!n) bad(std::string(name) + " is not a whole number: \"" + *value + "\"");
    return *n;
  };
  if (env("SLURM_ARRAY_TASK_ID")) {
    if (!env("SLURM_ARRAY_TASK_COUNT"))
      bad("SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not");
    const long long id = number("SLURM_ARRAY_TASK_ID", 0);
    const long long min = number("SLURM_ARRAY_TASK_MIN", 0);
    const long long step = number("SLURM_ARRAY_TASK_STEP", 1);
    if (step < 1) bad("SLURM_ARRAY_TASK_STEP must be >= 1");
    if ((id - min) % step != 0)
      bad("SLURM_ARRAY_TASK_ID " + std::to_string(id) + " is not on the array's step " +
          std::to_string(step) + " from " + std::to_string(min));
    return checked((id - min) / step, number("SLURM_ARRAY_TASK_COUNT", 1),
                   "Slurm array task " + std::to_string(id));
  }
  if (env("JOB_COMPLETION_INDEX")) {
    if (!shards)
      bad("JOB_COMPLETION_INDEX is set (a Kubernetes Indexed Job): give --shards N, the Job's "
          "completions");
    return checked(number("JOB_COMPLETION_INDEX", 0), static_cast<long long>(*shards),
                   "JOB_COMPLETION_INDEX");
  }
  if (shards)
    bad("--shards N needs JOB_COMPLETION_INDEX (a Kubernetes Indexed Job); use --shard I/N");
  return std::nullopt;
}

}  // namespace tumble::sweep
