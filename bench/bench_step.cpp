// Simulated steps per second of World::step() for the scenes the issue names, per integrator.
// Run: build/release/bench/bench_step   (figures go in the issue notes, never in a test).
#include <benchmark/benchmark.h>

#include "tumble/scene.hpp"
#include "tumble/world.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

constexpr Integrator kIntegrators[] = {Integrator::Euler, Integrator::SymplecticEuler,
                                       Integrator::Midpoint, Integrator::Rk4};

BodyDef unit_box(const Vec3& position) {
  BodyDef b;
  b.name = "box";
  b.inertia_body = box_inertia(1.0, Vec3::Ones());
  b.vertices = box_corners(Vec3::Ones());
  b.position = position;
  return b;
}

void run(benchmark::State& state, World world) {
  for (auto _ : state) {
    world.step();
    benchmark::DoNotOptimize(world.bodies()[0].state);
  }
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(std::string(to_string(world.def().integrator)));
}

// One unit box lying on the floor: static equilibrium, recognised and kept exactly.
void BM_BoxRestingOnFloor(benchmark::State& state) {
  WorldDef def;
  def.integrator = kIntegrators[state.range(0)];
  def.floor = FloorDef{};
  def.bodies.push_back(unit_box(Vec3(0, 0.5, 0)));
  run(state, World(def));
}

// One unit box sliding and spinning on a frictionless floor: never at rest, so every derivative
// evaluation needs its contact forces: the resting-face wrench (a 3×3 solve) by default; with
// range(1) = 1 the general LCP over its four bottom corners (the reference path).
void BM_BoxSlidingOnFloor(benchmark::State& state) {
  WorldDef def;
  def.integrator = kIntegrators[state.range(0)];
  def.floor = FloorDef{};
  BodyDef b = unit_box(Vec3(0, 0.5, 0));
  b.velocity = Vec3(1.0, 0.0, 0.5);
  b.angular_velocity = Vec3(0.0, 1.0, 0.0);
  def.bodies.push_back(b);
  def.general_contact_only = state.range(1) == 1;
  run(state, World(def));
  if (def.general_contact_only)
    state.SetLabel(std::string(to_string(def.integrator)) + " (general LCP)");
}

// The issue's awake-contact scenes at its settings (rk4, dt = 1e-5): a box sliding with
// friction μ = 0.5 (kinetic friction solved with the normal forces: the general LCP), and the
// chamfered die mesh (24 hull vertices, 8 on a face) spinning on its face without friction.
void BM_AwakeContact(benchmark::State& state) {
  Scene scene = parse_scene(state.range(0) == 0 ? R"([simulation]
dt = 1e-5
[floor]
friction = 0.5
[[body]]
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 0.5, 0.0]
velocity = [3.0, 0.0, 1.5]
angular_velocity = [0.0, 1.0, 0.0]
)"
                                                : R"([simulation]
dt = 1e-5
[floor]
[[body]]
shape = "mesh"
mesh = ")" + std::string(TUMBLE_SOURCE_DIR) + R"(/assets/meshes/die.obj"
mass = 1.0
position = [0.0, 0.5, 0.0]
velocity = [1.0, 0.0, 0.5]
angular_velocity = [0.0, 1.0, 0.0]
)",
                            "bench.toml");
  // 0.2 s from the start each time: the sliding box (3.35 m/s, losing mu g = 4.9 m/s per s)
  // slides throughout, instead of coming to rest and timing the exact rest path.
  const WorldDef def = make_world_def(scene);
  constexpr int kSteps = 20000;
  for (auto _ : state) {
    World world(def);
    for (int i = 0; i < kSteps; ++i) world.step();
    benchmark::DoNotOptimize(world.bodies()[0].state);
  }
  state.counters["steps/s"] = benchmark::Counter(kSteps * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
  state.SetLabel(state.range(0) == 0 ? "box sliding, mu = 0.5" : "die mesh spinning on a face");
}

// Torque-free tumble near the intermediate axis, no floor, no gravity.
void BM_TorqueFreeTumble(benchmark::State& state) {
  WorldDef def;
  def.integrator = kIntegrators[state.range(0)];
  def.gravity.setZero();
  BodyDef b;
  b.name = "box";
  b.inertia_body = box_inertia(1.0, Vec3(1, 2, 3));
  b.vertices = box_corners(Vec3(1, 2, 3));
  b.angular_velocity = Vec3(0.1, 4.0, 0.1);
  def.bodies.push_back(b);
  run(state, World(def));
}

// The whole default scene (4000 steps of the seed's drop: flight, impacts, rocking, rest).
void BM_DefaultSceneWholeRun(benchmark::State& state) {
  Scene scene = default_scene();
  scene.simulation.integrator = kIntegrators[state.range(0)];
  const WorldDef def = make_world_def(scene);
  for (auto _ : state) {
    World world(def);
    for (int i = 0; i < 4000; ++i) world.step();
    benchmark::DoNotOptimize(world.bodies()[0].state);
  }
  state.counters["steps/s"] = benchmark::Counter(4000.0 * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
  state.SetLabel(std::string(to_string(def.integrator)));
}

BENCHMARK(BM_BoxRestingOnFloor)->DenseRange(0, 3);
BENCHMARK(BM_BoxSlidingOnFloor)->ArgsProduct({{0, 1, 2, 3}, {0, 1}});
BENCHMARK(BM_AwakeContact)->DenseRange(0, 1);
BENCHMARK(BM_TorqueFreeTumble)->DenseRange(0, 3);
BENCHMARK(BM_DefaultSceneWholeRun)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tumble

BENCHMARK_MAIN();
