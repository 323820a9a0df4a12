// A job folder's state: finished only with a run.json of the same scene and version.
#include "tumble/job_folder.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "../test_dir.hpp"
#include "tumble/sweep_csv.hpp"

namespace tumble::sweep {
namespace {

namespace fs = std::filesystem;

void write_run_json(const fs::path& dir, const std::string& sha, const std::string& version) {
  std::ofstream(dir / "run.json") << R"({"tool": {"name": "tumble", "version": ")" << version
                                  << R"("}, "scene": {"path": "x", "sha256": ")" << sha
                                  << R"("}, "wall_time": {"total_s": 1.5}, "physics":
    {"energy_start_J": 29.4, "energy_end_J": 3.5, "contacts": 7},
    "outputs": [{"path": ")" << (dir / "clip.mp4").string()
                                  << R"(", "sha256": "ab12"}]})";
}

TEST(JobFolder, StatesFollowRunJsonAndErrorTxt) {
  const fs::path dir = test::fresh_dir("job_folder", "states");
  EXPECT_EQ(read_job_folder(dir, "s1", "0.1.0").state, JobState::Missing);
  EXPECT_EQ(read_job_folder(dir / "absent", "s1", "0.1.0").state, JobState::Missing);

  write_run_json(dir, "s1", "0.1.0");
  JobRecord r = read_job_folder(dir, "s1", "0.1.0");
  EXPECT_EQ(r.state, JobState::Finished);
  EXPECT_TRUE(r.complete);
  ASSERT_TRUE(r.facts);
  EXPECT_EQ(r.facts->contacts, 7);
  EXPECT_EQ(r.facts->energy_start_J, 29.4);
  ASSERT_EQ(r.facts->outputs.size(), 1u);
  EXPECT_EQ(r.facts->outputs[0].first, "clip.mp4");

  EXPECT_EQ(read_job_folder(dir, "other", "0.1.0").state, JobState::Stale);
  EXPECT_EQ(read_job_folder(dir, "s1", "0.2.0").state, JobState::Stale);
  std::ofstream(dir / "run.json") << "{ truncated";
  EXPECT_EQ(read_job_folder(dir, "s1", "0.1.0").state, JobState::Stale);

  clear_job_results(dir);
  EXPECT_FALSE(fs::exists(dir / "run.json"));
  write_error_file(dir, 2, "scene.toml:3:1: bad");
  r = read_job_folder(dir, "s1", "0.1.0");
  EXPECT_EQ(r.state, JobState::Failed);
  EXPECT_FALSE(r.complete);  // no run.json: it runs again
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.error, "scene.toml:3:1: bad");

  // --strict: run.json and error.txt, complete (the same run would flag the same) but failed.
  write_run_json(dir, "s1", "0.1.0");
  write_error_file(dir, 4, "flagged");
  r = read_job_folder(dir, "s1", "0.1.0");
  EXPECT_EQ(r.state, JobState::Failed);
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.exit_code, 4);
}

TEST(SweepCsv, QuotesFieldsThatNeedIt) {
  EXPECT_EQ(csv_field("0.5"), "0.5");
  EXPECT_EQ(csv_field("[0.0, 1.0]"), "\"[0.0, 1.0]\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("a\nb"), "\"a\nb\"");
}

}  // namespace
}  // namespace tumble::sweep
