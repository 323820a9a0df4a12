// Shards: --shard I/N, Slurm array tasks, Kubernetes Indexed Jobs; together they cover every
// job exactly once.
#include "tumble/shard.hpp"

#include <gtest/gtest.h>

#include <map>

#include "tumble/error.hpp"

namespace tumble::sweep {
namespace {

Environment env_of(std::map<std::string, std::string> values) {
  return [values](const char* name) -> std::optional<std::string> {
    const auto it = values.find(name);
    return it == values.end() ? std::nullopt : std::optional(it->second);
  };
}

int exit_code_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.exit_code();
  }
  return 0;
}

TEST(Shard, ShardsCoverEveryJobExactlyOnce) {
  for (std::size_t n = 1; n <= 5; ++n) {
    std::vector<int> hits(23, 0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < hits.size(); ++j)
        hits[j] += parse_shard(std::to_string(i) + "/" + std::to_string(n)).contains(j);
    for (const int h : hits) EXPECT_EQ(h, 1);
  }
}

TEST(Shard, ParsesAndChecksTheSpec) {
  const Shard s = parse_shard("2/4");
  EXPECT_EQ(s.index, 2u);
  EXPECT_EQ(s.count, 4u);
  EXPECT_TRUE(s.contains(6));
  EXPECT_FALSE(s.contains(7));
  for (const char* bad : {"4/4", "-1/4", "1/0", "1", "a/b", "1/2/3", "", "1/ 2"})
    EXPECT_EQ(exit_code_of([&] { parse_shard(bad); }), 2) << bad;
}

TEST(Shard, SlurmArrayTasksCountFromTheArraysMinimum) {
  const auto s = shard_from_environment(env_of({{"SLURM_ARRAY_TASK_ID", "12"},
                                                {"SLURM_ARRAY_TASK_MIN", "10"},
                                                {"SLURM_ARRAY_TASK_COUNT", "4"}}),
                                        std::nullopt);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->index, 2u);
  EXPECT_EQ(s->count, 4u);
  // --array=0-6:2 gives tasks 0, 2, 4, 6: four shards, task 6 the last.
  const auto stepped = shard_from_environment(env_of({{"SLURM_ARRAY_TASK_ID", "6"},
                                                      {"SLURM_ARRAY_TASK_MIN", "0"},
                                                      {"SLURM_ARRAY_TASK_STEP", "2"},
                                                      {"SLURM_ARRAY_TASK_COUNT", "4"}}),
                                              std::nullopt);
  ASSERT_TRUE(stepped);
  EXPECT_EQ(stepped->index, 3u);
  EXPECT_EQ(exit_code_of([&] {
              shard_from_environment(
                  env_of({{"SLURM_ARRAY_TASK_ID", "5"}, {"SLURM_ARRAY_TASK_COUNT", "4"}}),
                  std::nullopt);
            }),
            2);
}

TEST(Shard, KubernetesIndexedJobsNeedShards) {
  const auto s = shard_from_environment(env_of({{"JOB_COMPLETION_INDEX", "3"}}), 5);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->index, 3u);
  EXPECT_EQ(s->count, 5u);
  EXPECT_EQ(exit_code_of([&] {
              shard_from_environment(env_of({{"JOB_COMPLETION_INDEX", "3"}}), std::nullopt);
            }),
            2);
  EXPECT_EQ(exit_code_of([&] {
              shard_from_environment(env_of({{"JOB_COMPLETION_INDEX", "5"}}), 5);
            }),
            2);
  EXPECT_EQ(exit_code_of([&] { shard_from_environment(env_of({}), 5); }), 2);
  EXPECT_FALSE(shard_from_environment(env_of({}), std::nullopt));
}

}  // namespace
}  // namespace tumble::sweep
