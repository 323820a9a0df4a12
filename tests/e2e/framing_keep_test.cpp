// A framed render (no camera position) simulates the run once to place the camera and keeps the
// worlds it sampled for drawing, within a byte budget, so the run is not simulated again: the
// outputs must be the very bytes of a render that keeps nothing (the hidden
// --framing-keep-bytes 0: the two passes as before) or only the first part of the run, and
// run.json the same physics, with the pass's time in wall_time.framing_s.
#include <gtest/gtest.h>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

std::vector<std::string> with(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

// Renders `args` keeping every world (the default), none, and about the first third; every
// output file and run.json's physics must match.
void expect_same_outputs_whatever_is_kept(const TestDir& dir, const std::vector<std::string>& args,
                                          const std::string& part_bytes) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
      {"kept", {}},
      {"none", {"--framing-keep-bytes", "0"}},
      {"part", {"--framing-keep-bytes", part_bytes}}};
  for (const auto& [out, extra] : runs) {
    const RunResult r =
        run_tumble(with(with({"render", "--quiet", "--out", out}, args), extra), dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
  }
  const nlohmann::json none = read_json(dir / "none/run.json");
  for (const char* out : {"kept", "part"}) {
    std::size_t files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(dir / "none")) {
      if (!entry.is_regular_file() || entry.path().filename() == "run.json") continue;
      const fs::path rel = fs::relative(entry.path(), dir / "none");
      ++files;
      EXPECT_TRUE(read_file(dir / out / rel) == read_file(entry.path()))
          << out << "/" << rel.string() << " differs from a render that keeps nothing";
    }
    EXPECT_GE(files, 3u);  // three stills at least
    const nlohmann::json j = read_json(dir / out / "run.json");
    ASSERT_EQ(j["outputs"].size(), none["outputs"].size()) << out;
    for (std::size_t i = 0; i < none["outputs"].size(); ++i)
      EXPECT_EQ(j["outputs"][i]["sha256"], none["outputs"][i]["sha256"]) << out << " " << i;
    EXPECT_EQ(j["counts"], none["counts"]) << out;
    EXPECT_EQ(j["physics"], none["physics"]) << out;
    EXPECT_EQ(j["diagnostics"], none["diagnostics"]) << out;
    EXPECT_EQ(j["settings"]["camera"], none["settings"]["camera"]) << out;
    ASSERT_TRUE(j["wall_time"].contains("framing_s")) << j["wall_time"].dump();
    EXPECT_GT(j["wall_time"]["framing_s"].get<double>(), 0.0);
  }
  EXPECT_TRUE(none["settings"]["camera"]["framed"].get<bool>());
}

TEST(FramingKeep, DefaultSceneSameBytesWhateverTheBudget) {
  // Frames, a still and a strobe between them, a clip and PNG frames: about 15 kB of kept
  // worlds for 1.5 s at 60 fps; 5 000 bytes keep the first few dozen.
  const TestDir dir;
  expect_same_outputs_whatever_is_kept(
      dir, {"--duration", "1.5", "--size", "96x64", "--png", "--still", "0.7", "--strobe", "3"},
      "5000");
}

TEST(FramingKeep, StillsOnlyKeepTheirExposures) {
  const TestDir dir;
  expect_same_outputs_whatever_is_kept(dir,
                                       {"--duration", "2", "--size", "96x64", "--no-mp4", "--still",
                                        "0.5", "--still", "1.25", "--still", "2"},
                                       "2000");
}

TEST(FramingKeep, AStatedCameraHasNoFramingPass) {
  const TestDir dir;
  write_scene(dir.path(), "placed.toml", R"([simulation]
duration = 0.5
[render]
fps = 30
[camera]
position = [5.0, 3.0, 6.0]
[[body]]
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 1.0, 0.0]
)");
  const RunResult r =
      run_tumble({"render", "placed.toml", "--quiet", "--size", "64x48", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_FALSE(j["wall_time"].contains("framing_s")) << j["wall_time"].dump();
  EXPECT_TRUE(j["wall_time"].contains("simulate_s"));
}

}  // namespace
}  // namespace tumble_e2e
