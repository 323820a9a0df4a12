// A plan's jobs: job i's grid point and random draws, a pure function of the plan and i.
#include <cassert>
#include <cstdio>

#include "toml_text.hpp"
#include "tumble/split_mix.hpp"
#include "tumble/sweep.hpp"

namespace tumble::sweep {
namespace {

std::string draw(const Distribution& d, SplitMix64& random) {
  using Kind = Distribution::Kind;
  switch (d.kind) {
    case Kind::Integer:
      return std::to_string(random.integer(d.lo, d.hi));
    case Kind::Choice:
      return d.choices[static_cast<std::size_t>(
          random.integer(0, static_cast<std::int64_t>(d.choices.size()) - 1))];
    case Kind::Uniform:
    case Kind::Normal:
      break;
  }
  // Components are drawn in order from the key's one stream.
  std::string text;
  for (std::size_t i = 0; i < d.first.size(); ++i) {
    const double x = d.kind == Kind::Uniform ? random.uniform(d.first[i], d.second[i])
                                             : random.normal(d.first[i], d.second[i]);
    text += (i ? ", " : "") + toml_number(x + 0.0);  // + 0.0: -0 is written as 0
  }
  return d.vector ? "[" + text + "]" : text;
}

}  // namespace

Job make_job(const Plan& plan, std::size_t index) {
  assert(index < plan.job_count());
  Job job;
  job.index = index;
  const std::size_t count = plan.random_count.value_or(1);
  // Grid point index / count, written in mixed radix with the last axis varying fastest.
  std::size_t point = index / count;
  std::vector<std::size_t> choice(plan.grid.size());
  for (std::size_t a = plan.grid.size(); a-- > 0;) {
    choice[a] = point % plan.grid[a].values.size();
    point /= plan.grid[a].values.size();
  }
  for (std::size_t a = 0; a < plan.grid.size(); ++a) {
    const GridAxis& axis = plan.grid[a];
    job.parameters.push_back({&axis.key, axis.values[choice[a]], axis.value_at[choice[a]]});
  }
  for (std::size_t k = 0; k < plan.random.size(); ++k) {
    const RandomKey& r = plan.random[k];
    SplitMix64 random = SplitMix64::stream(plan.seed, index, k);
    job.parameters.push_back({&r.key, draw(r.distribution, random), r.key.value_at});
  }
  return job;
}

std::string job_folder_name(std::size_t index) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "job_%05zu", index);
  return buffer;
}

}  // namespace tumble::sweep
