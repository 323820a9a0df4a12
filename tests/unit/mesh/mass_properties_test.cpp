// Mass properties by the divergence theorem against closed forms: boxes (exact to round-off,
// since every integrand is a polynomial the formulas integrate exactly), tetrahedra (the
// covariance closed form), the icosphere, the L-shape; and the principal frame's choices.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "mesh_fixtures.hpp"

namespace tumble {
namespace {

using test::box_inertia_unit_density;
using test::box_mesh;
using test::relative_difference;
using test::shifted_inertia;

// Exact polynomial integration over a dozen triangles: only round-off, a few ulps.
constexpr double kExact = 1e-12;

TEST(MassProperties, UnitCubeIsTheAnalyticBox) {
  const MassProperties m = mass_properties(box_mesh(Vec3::Ones()));
  EXPECT_NEAR(m.volume, 1.0, kExact);
  EXPECT_LT(m.center_of_mass.norm(), kExact);
  EXPECT_LT(relative_difference(m.inertia_com, box_inertia_unit_density(Vec3::Ones())), kExact);
  EXPECT_TRUE(m.principal_axes.isIdentity(0.0));  // isotropic: the file's axes, exactly
  EXPECT_LT((m.principal_moments - Vec3::Constant(1.0 / 6.0)).norm(), kExact);
}

TEST(MassProperties, OffsetBoxKeepsItsAxesAndMomentsInFileOrder) {
  const Vec3 size(1.0, 2.0, 3.0), centre(10.0, -20.0, 5.0);
  const MassProperties m = mass_properties(box_mesh(size, centre));
  EXPECT_NEAR(m.volume, 6.0, 6.0 * kExact);
  EXPECT_LT((m.center_of_mass - centre).norm(), 20.0 * kExact);
  const Mat3 exact = box_inertia_unit_density(size);
  EXPECT_LT(relative_difference(m.inertia_com, exact), kExact);
  // Distinct moments, box-aligned: the nearest rotation to identity is identity, and the
  // moments stay in x, y, z order (what box_inertia() gives the box shape).
  EXPECT_LT((m.principal_axes - Mat3::Identity()).norm(), 1e-12);
  EXPECT_LT((m.principal_moments - exact.diagonal()).norm(), kExact * exact.norm());
}

TEST(MassProperties, TetrahedronMatchesTheCovarianceClosedForm) {
  // Any tetrahedron: ∫ r rᵀ dV about the origin = V/20 (Σ v_i v_iᵀ + s sᵀ), s = Σ v_i; its
  // centroid is s/4 (Tonon 2004).
  const std::vector<Vec3> v = {{0.1, 0.2, -0.3}, {1.7, 0.1, 0.4}, {0.3, 1.1, 0.2}, {0.5, 0.4, 2.0}};
  TriangleMesh mesh;
  mesh.vertices = v;
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const double volume = (v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0])) / 6.0;
  ASSERT_GT(volume, 0.0);
  const Vec3 s = v[0] + v[1] + v[2] + v[3];
  Mat3 covariance = s * s.transpose();
  for (const Vec3& p : v) covariance += p * p.transpose();
  covariance *= volume / 20.0;
  const Vec3 centroid = s / 4.0;
  const Mat3 about_centroid = covariance - volume * centroid * centroid.transpose();
  const Mat3 inertia = about_centroid.trace() * Mat3::Identity() - about_centroid;

  const MassProperties m = mass_properties(mesh);
  EXPECT_NEAR(m.volume, volume, volume * kExact);
  EXPECT_LT((m.center_of_mass - centroid).norm(), kExact);
  EXPECT_LT(relative_difference(m.inertia_com, inertia), kExact);
  // The principal frame diagonalises the tensor.
  const Mat3 back =
      m.principal_axes * m.principal_moments.asDiagonal() * m.principal_axes.transpose();
  EXPECT_LT(relative_difference(back, inertia), 1e-12);
  EXPECT_NEAR(m.principal_axes.determinant(), 1.0, 1e-12);
}

TEST(MassProperties, RegularTetrahedronAssetIsIsotropic) {
  // Alternate corners of the cube [-1/2, 1/2]^3: edge a = sqrt(2), V = a^3/(6 sqrt 2) = 1/3,
  // I = m a^2 / 20 = V/10 about every axis. Exact coordinates, so round-off only.
  const MeshBody body = test::load(test::kAssets / "tetrahedron.obj");
  EXPECT_NEAR(body.mass.volume, 1.0 / 3.0, kExact);
  EXPECT_LT(body.mass.center_of_mass.norm(), kExact);
  EXPECT_LT(relative_difference(body.mass.inertia_com, Mat3::Identity() / 30.0), kExact);
  EXPECT_TRUE(body.mass.principal_axes.isIdentity(0.0));
  EXPECT_EQ(body.hull_vertices.size(), 4u);
  EXPECT_EQ(body.hull_faces, 4u);
}

// The icosphere of subdivision 2 as scripts/make-meshes builds it, in double precision.
TriangleMesh icosphere(int subdivisions, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh m;
  m.vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& v : m.vertices) v.normalize();
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      m.vertices.push_back((0.5 * (m.vertices[a] + m.vertices[b])).normalized());
      const auto index = static_cast<std::uint32_t>(m.vertices.size() - 1);
      middle[key] = index;
      return index;
    };
    std::vector<std::array<std::uint32_t, 3>> refined;
    for (const auto& [a, b, c] : m.triangles) {
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      refined.push_back({a, ab, ca});
      refined.push_back({b, bc, ab});
      refined.push_back({c, ca, bc});
      refined.push_back({ab, bc, ca});
    }
    m.triangles = refined;
  }
  for (Vec3& v : m.vertices) v *= radius;
  return m;
}

TEST(MassProperties, IcosphereMatchesItsPolyhedronAndNearlyTheSphere) {
  // The exact polyhedron volume: Σ over faces of the tetrahedron (centre, face), each
  // |a.(b x c)|/6, which needs no orientation. The asset stores float32 coordinates
  // (relative error 6e-8 each), so compare to 1e-6.
  const TriangleMesh exact = icosphere(2, 0.5);
  double volume = 0.0;
  for (const auto& [a, b, c] : exact.triangles)
    volume += std::abs(exact.vertices[a].dot(exact.vertices[b].cross(exact.vertices[c]))) / 6.0;
  const MeshBody body = test::load(test::kAssets / "icosphere.obj");
  EXPECT_EQ(body.mesh.triangles.size(), 320u);
  EXPECT_EQ(body.welded_vertices, 162u);
  EXPECT_NEAR(body.mass.volume / volume, 1.0, 1e-6);
  // Inscribed in the sphere of radius 0.5: 3.4% short of its volume at 320 faces.
  const double sphere = 4.0 / 3.0 * kPi * 0.125;
  EXPECT_LT(body.mass.volume, sphere);
  EXPECT_GT(body.mass.volume, 0.96 * sphere);
  // Icosahedral symmetry makes the inertia isotropic: (2/5) m r² for the sphere, a little
  // less for the inscribed polyhedron; the file's axes are kept.
  const Vec3& moments = body.mass.principal_moments;
  EXPECT_LT((moments.maxCoeff() - moments.minCoeff()) / moments.maxCoeff(), 1e-6);
  EXPECT_NEAR(moments.x() / (0.4 * body.mass.volume * 0.25), 1.0, 0.04);
  EXPECT_TRUE(body.mass.principal_axes.isIdentity(0.0));
  EXPECT_LT(body.mass.center_of_mass.norm(), 1e-7);
}

TEST(MassProperties, LShapeCentreOfMassIsOffItsBoundingBoxCentre) {
  // Two boxes: A = [0,1]x[0,1/2]x[0,1/2] (V 1/4) and B = [0,1/2]x[1/2,1]x[0,1/2] (V 1/8).
  const MeshBody body = test::load(test::kAssets / "lshape.obj");
  const Vec3 ca(0.5, 0.25, 0.25), cb(0.25, 0.75, 0.25);
  const double va = 0.25, vb = 0.125;
  const Vec3 com = (va * ca + vb * cb) / (va + vb);  // (5/12, 5/12, 1/4)
  EXPECT_NEAR(body.mass.volume, 0.375, kExact);
  EXPECT_LT((body.mass.center_of_mass - com).norm(), kExact);
  EXPECT_LT((body.mass.center_of_mass - Vec3(5.0 / 12.0, 5.0 / 12.0, 0.25)).norm(), kExact);
  EXPECT_GT((body.mass.center_of_mass - Vec3(0.5, 0.5, 0.25)).norm(), 0.1);  // bbox centre
  const Mat3 inertia =
      shifted_inertia(box_inertia_unit_density(Vec3(1.0, 0.5, 0.5)), va, ca - com) +
      shifted_inertia(box_inertia_unit_density(Vec3(0.5, 0.5, 0.5)), vb, cb - com);
  EXPECT_LT(relative_difference(body.mass.inertia_com, inertia), kExact);
  // Non-convex: the hull has the 5 corners of the profile's convex outline at both ends; the
  // inner corner (1/2, 1/2) lies inside it.
  EXPECT_EQ(body.hull_vertices.size(), 10u);
}

TEST(MassProperties, ScalePerAxisScalesVolumeAndInertia) {
  const Vec3 scale(2.0, 0.5, 3.0);
  const MeshBody body = test::load(test::kAssets / "cube.obj", MeshRepair::None, scale);
  EXPECT_NEAR(body.mass.volume, 3.0, 3.0 * kExact);
  EXPECT_LT(relative_difference(body.mass.inertia_com, box_inertia_unit_density(scale)), kExact);
  EXPECT_LT((body.mass.principal_axes - Mat3::Identity()).norm(), 1e-12);
  for (const Vec3& v : body.hull_vertices) EXPECT_LT((v.cwiseAbs() - 0.5 * scale).norm(), kExact);
}

TEST(MassProperties, InsideOutMeshHasNegativeVolume) {
  TriangleMesh mesh = box_mesh(Vec3::Ones());
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  EXPECT_NEAR(mass_properties(mesh).volume, -1.0, kExact);
}

TEST(PrincipalFrame, RotatedBoxRecoversItsRotationNearestIdentity) {
  const Mat3 rotation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized())).toRotationMatrix();
  const Mat3 body = Vec3(1.0, 2.0, 3.0).asDiagonal();
  const PrincipalFrame frame = principal_frame(rotation * body * rotation.transpose());
  EXPECT_LT((frame.axes - rotation).norm(), 1e-12);
  EXPECT_LT((frame.moments - Vec3(1.0, 2.0, 3.0)).norm(), 1e-12);
  EXPECT_NEAR(frame.axes.determinant(), 1.0, 1e-12);
}

TEST(PrincipalFrame, TwoEqualMomentsKeepTheFileAxesInTheirPlane) {
  // A square plate about y: Ixx = Izz. Rotated about y, any axes in the x-z plane are
  // principal; the frame must keep x and z, not an arbitrary pair.
  const Mat3 plate = Vec3(2.0, 4.0, 2.0).asDiagonal();
  const PrincipalFrame frame = principal_frame(plate);
  EXPECT_TRUE(frame.axes.isIdentity(1e-12));
  EXPECT_LT((frame.moments - Vec3(2.0, 4.0, 2.0)).norm(), 1e-12);
  // Tilted about x: the unique axis becomes R e_y; the others are the nearest to x and z.
  const Mat3 r = Eigen::AngleAxisd(0.3, Vec3::UnitX()).toRotationMatrix();
  const PrincipalFrame tilted = principal_frame(r * plate * r.transpose());
  EXPECT_LT((tilted.axes - r).norm(), 1e-12);
}

TEST(PrincipalFrame, NearlyEqualMomentsCountAsEqual) {
  // Float32 noise on a cube's coordinates: moments equal to 1e-7; the axes stay identity.
  Mat3 inertia = Mat3::Identity();
  inertia(0, 1) = inertia(1, 0) = 1e-8;
  inertia(2, 2) = 1.0 + 1e-7;
  const PrincipalFrame frame = principal_frame(inertia);
  EXPECT_TRUE(frame.axes.isIdentity(0.0));
  EXPECT_NEAR(frame.moments.sum(), inertia.trace(), 1e-15);
}

TEST(PrincipalFrame, AxesAreRightHandedAndDiagonalise) {
  const Mat3 a = (Mat3() << 3.0, 0.4, -0.2, 0.4, 2.5, 0.1, -0.2, 0.1, 1.2).finished();
  const PrincipalFrame f = principal_frame(a);
  EXPECT_NEAR(f.axes.determinant(), 1.0, 1e-12);
  EXPECT_LT((f.axes * f.moments.asDiagonal() * f.axes.transpose() - a).norm(), 1e-12);
  EXPECT_GT(f.axes.trace(), 0.0);
}

}  // namespace
}  // namespace tumble
