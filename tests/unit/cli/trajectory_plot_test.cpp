// trajectory.svg's impact marks: bounces only (not contact coming to rest), close ones merged,
// and a body's name only where the impact before was another body's.
#include "trajectory_plot.hpp"

#include <gtest/gtest.h>

#include "tumble/scene.hpp"
#include "tumble/world_builder.hpp"

namespace tumble::cli {
namespace {

constexpr const char* kTwoBoxes = R"(
[simulation]
duration = 2.0
[floor]
[[body]]
name = "top"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 3.0, 0.0]
[[body]]
name = "bottom"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [3.0, 1.0, 0.0]
)";

TEST(TrajectoryPlot, MarksBouncesNotContactComingToRest) {
  const Scene scene = parse_scene(kTwoBoxes, "two.toml", {});
  const World world(make_world_def(scene));
  const double rest = world.tolerances(0).rest_speed_mps;  // the same for both (same size)
  TrajectoryPlot plot("two", 2.0, 3);
  plot.add(0, 0.0, world);
  const std::vector<ImpactEvent> events = {
      {0.50, 0, 3.0},         // a bounce of "top"
      {0.5005, 0, 2.9},       // its other corners, within a thousandth of the run: one line
      {0.70, 0, 0.5 * rest},  // "top" settling onto its face: not an impact
      {1.00, 0, 1.5},         // "top" again: marked, its name not repeated
      {1.20, 1, 2.0},         // "bottom": named
      {1.40, 0, rest},        // "top" at the rest speed exactly: a (last) bounce, named again
  };
  const std::vector<TrajectoryPlot::ImpactMark> marks = plot.impact_marks(events);
  ASSERT_EQ(marks.size(), 4u);
  EXPECT_EQ(marks[0].t_s, 0.50);
  EXPECT_EQ(marks[0].label, "top");
  EXPECT_EQ(marks[1].t_s, 1.00);
  EXPECT_EQ(marks[1].label, "");
  EXPECT_EQ(marks[2].label, "bottom");
  EXPECT_EQ(marks[3].t_s, 1.40);
  EXPECT_EQ(marks[3].label, "top");
  // In the figure: four lines, and "top" written twice, "bottom" once.
  const std::string svg = plot.svg(events);
  std::size_t tops = 0;
  for (std::size_t at = svg.find(">top</text>"); at != std::string::npos;
       at = svg.find(">top</text>", at + 1))
    ++tops;
  EXPECT_EQ(tops, 2u + 2u) << "two marks and the two legend entries";
}

}  // namespace
}  // namespace tumble::cli
