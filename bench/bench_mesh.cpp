// Cost of making a rigid body from a 100 000-triangle closed model: the whole load_mesh_body
// (assimp import, welding, topology, orientation, mass properties, hull, checks) from OBJ and
// from binary STL, and its two geometric parts alone. The model is a torus of 250 x 200 quads
// written to a temporary folder (non-convex, so the hull is real work).
// Run: build/release/bench/bench_mesh   (figures go in the issue notes, never in a test).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "tumble/mesh.hpp"

namespace tumble {
namespace {

constexpr int kAround = 250, kTube = 200;  // 2 * 250 * 200 = 100 000 triangles

TriangleMesh torus() {
  TriangleMesh m;
  const double major = 1.0, minor = 0.3;
  for (int i = 0; i < kAround; ++i)
    for (int j = 0; j < kTube; ++j) {
      const double u = 2.0 * kPi * i / kAround, v = 2.0 * kPi * j / kTube;
      m.vertices.emplace_back((major + minor * std::cos(v)) * std::cos(u), minor * std::sin(v),
                              (major + minor * std::cos(v)) * std::sin(u));
    }
  auto at = [](int i, int j) {
    return static_cast<std::uint32_t>((i % kAround) * kTube + (j % kTube));
  };
  for (int i = 0; i < kAround; ++i)
    for (int j = 0; j < kTube; ++j) {
      // Outward: (d/dv) x (d/du) points away from the tube's core.
      m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  return m;
}

const std::filesystem::path& model_folder() {
  static const std::filesystem::path folder = [] {
    const auto dir = std::filesystem::temp_directory_path() / "tumble_bench_mesh";
    std::filesystem::create_directories(dir);
    const TriangleMesh m = torus();
    std::FILE* obj = std::fopen((dir / "torus.obj").c_str(), "w");
    for (const Vec3& v : m.vertices) std::fprintf(obj, "v %.9g %.9g %.9g\n", v.x(), v.y(), v.z());
    for (const auto& t : m.triangles)
      std::fprintf(obj, "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1);
    std::fclose(obj);
    std::ofstream stl(dir / "torus.stl", std::ios::binary);
    char header[80] = "tumble bench_mesh torus";
    stl.write(header, sizeof header);
    const auto count = static_cast<std::uint32_t>(m.triangles.size());
    stl.write(reinterpret_cast<const char*>(&count), sizeof count);
    for (const auto& t : m.triangles) {
      const Vec3 n = (m.vertices[t[1]] - m.vertices[t[0]])
                         .cross(m.vertices[t[2]] - m.vertices[t[0]])
                         .normalized();
      float record[12];
      for (int k = 0; k < 3; ++k) record[k] = static_cast<float>(n[k]);
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k)
          record[3 + 3 * c + k] = static_cast<float>(m.vertices[t[static_cast<std::size_t>(c)]][k]);
      stl.write(reinterpret_cast<const char*>(record), sizeof record);
      const std::uint16_t attributes = 0;
      stl.write(reinterpret_cast<const char*>(&attributes), sizeof attributes);
    }
    return dir;
  }();
  return folder;
}

void load(benchmark::State& state, const char* name) {
  const auto file = model_folder() / name;
  std::size_t hull = 0;
  for (auto _ : state) {
    const MeshBody body = load_mesh_body(file, {});
    hull = body.hull_vertices.size();
    benchmark::DoNotOptimize(body.mass.volume);
  }
  state.counters["triangles"] = 2.0 * kAround * kTube;
  state.counters["hull_vertices"] = static_cast<double>(hull);
}

void BM_LoadMeshBodyObj(benchmark::State& state) {
  load(state, "torus.obj");
}
void BM_LoadMeshBodyBinaryStl(benchmark::State& state) {
  load(state, "torus.stl");
}

void BM_MassProperties(benchmark::State& state) {
  const TriangleMesh m = torus();
  for (auto _ : state) benchmark::DoNotOptimize(mass_properties(m).volume);
}

void BM_ConvexHull(benchmark::State& state) {
  const TriangleMesh m = torus();
  for (auto _ : state) benchmark::DoNotOptimize(convex_hull(m.vertices).faces);
}

BENCHMARK(BM_LoadMeshBodyObj)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LoadMeshBodyBinaryStl)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MassProperties)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ConvexHull)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tumble

BENCHMARK_MAIN();
