#pragma once
// Shared helpers for the mesh tests: where the models are, closed forms of boxes, and building
// small meshes in code.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tumble/error.hpp"
#include "tumble/mesh.hpp"

/// Expects `text` to contain `part`, showing the whole text when it does not.
#define EXPECT_CONTAINS(text, part)                                                          \
  do {                                                                                       \
    const std::string tumble_text_ = (text);                                                 \
    EXPECT_NE(tumble_text_.find(part), std::string::npos)                                    \
        << "expected to contain: " << (part) << "\n                  got: " << tumble_text_; \
  } while (false)

namespace tumble::test {

inline const std::filesystem::path kAssets =
    std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets" / "meshes";
inline const std::filesystem::path kData =
    std::filesystem::path(TUMBLE_SOURCE_DIR) / "tests" / "unit" / "mesh" / "data";

inline MeshBody load(const std::filesystem::path& file, MeshRepair repair = MeshRepair::None,
                     const Vec3& scale = Vec3::Ones()) {
  MeshLoadOptions options;
  options.repair = repair;
  options.scale = scale;
  return load_mesh_body(file, options);
}

/// The text `describe()` gives for the error loading `file` throws ("" when it loads).
inline std::string load_error(const std::filesystem::path& file,
                              const MeshLoadOptions& options = {}) {
  try {
    load_mesh_body(file, options);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    return e.describe();
  }
  return "";
}

/// Inertia of a solid box about its centre at unit density: V/12 (b² + c², ...), diagonal.
inline Mat3 box_inertia_unit_density(const Vec3& size) {
  const double v = size.prod();
  const Vec3 s2 = size.cwiseProduct(size);
  return (v / 12.0 * Vec3(s2.y() + s2.z(), s2.z() + s2.x(), s2.x() + s2.y())).asDiagonal();
}

/// Parallel-axis shift of an inertia tensor from a body's centre to a point `d` away from it.
inline Mat3 shifted_inertia(const Mat3& inertia_com, double volume, const Vec3& d) {
  return inertia_com + volume * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
}

/// An axis-aligned box as a mesh: 8 corners, 12 outward triangles.
inline TriangleMesh box_mesh(const Vec3& size, const Vec3& centre = Vec3::Zero()) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back(
        centre + 0.5 * size.cwiseProduct(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
  // Corners: bit 0 = +x, bit 1 = +y, bit 2 = +z. Each face counter-clockwise from outside.
  m.triangles = {{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5},   // -x, +x
                 {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},   // -y, +y
                 {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};  // -z, +z
  return m;
}

/// Largest entry of |a - b| relative to the largest entry of |b|.
inline double relative_difference(const Mat3& a, const Mat3& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

}  // namespace tumble::test
