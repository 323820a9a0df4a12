#pragma once
/// A rigid body in the Baraff–Witkin formulation: constant mass properties in the body frame
/// (principal axes through the centre of mass, so the body inertia tensor is diagonal) and a state
/// Y = (x, q or R, P, L). Velocities are derived: v = P/m, I⁻¹ = R I_body⁻¹ Rᵀ, ω = I⁻¹ L.
/// A particle carries (x, P) only: its orientation and angular momentum are never integrated.

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tumble/integrators.hpp"
#include "tumble/math.hpp"

namespace tumble {

/// The state vector Y of one body. Both orientation forms are kept: the live one is chosen by
/// the world's RotationRep and integrated; the other is derived from it after every step.
struct BodyState {
  Vec3 x = Vec3::Zero();  ///< centre of mass, world, m
  Quat q = Quat::Identity();
  Mat3 R = Mat3::Identity();
  Vec3 P = Vec3::Zero();  ///< linear momentum, kg·m/s
  Vec3 L = Vec3::Zero();  ///< angular momentum about the centre of mass, world, kg·m²/s
};

/// The shape a body collides with. A box and a mesh are both convex polyhedra (a mesh as its
/// convex hull); a sphere has a radius and full rotation; a particle is a point.
enum class ShapeKind { Particle, Sphere, Box, Hull };

/// A face of a convex polyhedron in the body frame: its outward unit normal and its corners
/// (indices into the body's vertices), counter-clockwise seen from outside.
struct HullFace {
  Vec3 normal = Vec3::UnitY();
  std::vector<int> vertices;
};

/// What the simulation needs to know of a body: plain data, built by the scene layer.
struct BodyDef {
  std::string name;
  bool particle = false;
  ShapeKind shape = ShapeKind::Box;  ///< kept consistent with `particle` by the builder
  double radius_m = 0.0;             ///< sphere only
  /// Faces of a box or hull (body frame, over `vertices`); empty for spheres and particles.
  std::vector<HullFace> faces;
  /// Does not move: infinite mass, never integrated, never meets the floor or another fixed
  /// body (ramps, tables, walls, pegs).
  bool fixed = false;
  /// Coulomb mu of the body (SPEC per-body `friction`); none: the floor's (0 without a floor).
  std::optional<double> friction;
  double mass_kg = 1.0;
  Vec3 inertia_body = Vec3::Ones();  ///< principal moments, kg·m² (unused for a particle)
  std::vector<Vec3> vertices;        ///< contact points in the body frame (box: its 8 corners)
  double restitution = 0.5;          ///< against the floor, in [0, 1]
  /// Characteristic length ℓ for the scale of contact tolerances; 0 = the vertices' largest
  /// extent (a particle, whose one vertex spans nothing, gets its drawn size from the scene).
  double length_m = 0.0;
  /// A model's principal axes as a rotation from the body frame to the model's (file's) frame,
  /// and its centre of mass in the model frame. Boxes and particles: identity and zero. The
  /// simulation works in the principal frame; `orientation` and what users see are the model's.
  Quat principal_axes = Quat::Identity();
  Vec3 com_offset = Vec3::Zero();
  Vec3 position = Vec3::Zero();         ///< centre of mass, world
  Quat orientation = Quat::Identity();  ///< of the model frame
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();  ///< world frame, rad/s
};

/// True when `a` and `b` put a body at bitwise the same place and orientation (x, q and R):
/// whatever is drawn of one is drawn the same of the other. Momenta are not compared.
bool same_pose(const BodyState& a, const BodyState& b);

/// Principal moments of a solid box of full edge lengths `size`: m/12 (b² + c²), ...
Vec3 box_inertia(double mass_kg, const Vec3& size);
/// The 8 corners of a box of full edge lengths `size`, centred on the origin.
std::vector<Vec3> box_corners(const Vec3& size);
/// The 6 faces of the box whose corners box_corners gives (corner i has bit 0 = +x, 1 = +y,
/// 2 = +z), counter-clockwise from outside.
std::vector<HullFace> box_faces();
/// Principal moments of a solid sphere: 2/5 m r² about every axis.
Vec3 sphere_inertia(double mass_kg, double radius_m);
/// The faces of a convex polyhedron from its outward-wound triangles: coplanar neighbours
/// (normals within 1e-9) merged into one polygon, corners counter-clockwise from outside.
std::vector<HullFace> faces_from_triangles(const std::vector<Vec3>& vertices,
                                           const std::vector<std::array<int, 3>>& triangles);

class RigidBody {
 public:
  explicit RigidBody(const BodyDef& def);

  const std::string& name() const { return name_; }
  bool is_particle() const { return particle_; }
  ShapeKind shape() const { return shape_; }
  bool is_sphere() const { return shape_ == ShapeKind::Sphere; }
  bool is_fixed() const { return fixed_; }
  double radius() const { return radius_; }
  const std::vector<HullFace>& faces() const { return geometry_->faces; }
  /// The distinct directions of the polyhedron's edges (body frame, unit): the edge axes of the
  /// separating-axis test. Empty for spheres and particles.
  const std::vector<Vec3>& edge_directions() const { return geometry_->edge_directions; }
  /// Distance from the centre of mass to the farthest point of the shape.
  double bounding_radius() const { return bounding_radius_; }
  /// Half the edges of the smallest box about the centre of mass, along the body's axes, that
  /// holds the shape (zero for a particle).
  const Vec3& half_extent_body() const { return half_extent_body_; }
  /// Half the edges of a world-axis box about the centre of mass that holds the shape at
  /// orientation R: the body box's, |R| h, and never more than the bounding sphere's.
  Vec3 half_extent_world(const Mat3& R) const {
    return (R.cwiseAbs() * half_extent_body_).cwiseMin(Vec3::Constant(bounding_radius_));
  }
  double mass() const { return mass_; }
  double inverse_mass() const { return inverse_mass_; }
  const Vec3& inertia_body() const { return inertia_body_; }
  const Vec3& inverse_inertia_body() const { return inverse_inertia_body_; }
  const std::vector<Vec3>& vertices() const { return geometry_->vertices; }
  double restitution() const { return restitution_; }
  /// Contact vertex i relative to the centre of mass in world axes, for orientation R: R v_i,
  /// or for a sphere (one vertex) the point of it lowest along y, (0, -r, 0) whatever R.
  Vec3 vertex_offset(const Mat3& R, int i) const {
    return shape_ == ShapeKind::Sphere ? Vec3(0.0, -radius_, 0.0)
                                       : Vec3(R * geometry_->vertices[i]);
  }

  BodyState state;
  /// True once the body rests in static equilibrium on the floor (see World): its exact motion
  /// is then no motion, so it is not integrated.
  bool at_rest = false;

  Vec3 velocity() const { return state.P * inverse_mass_; }
  /// Orientation of the model's own frame (as its file has it): the body's principal frame
  /// rotated back by the principal axes. The state's q for boxes and particles.
  Quat model_orientation() const {
    return identity_axes_ ? state.q : Quat(state.q * principal_axes_.conjugate());
  }
  const Quat& principal_axes() const { return principal_axes_; }
  /// Centre of mass in the model frame (zero for boxes and particles).
  const Vec3& com_offset() const { return com_offset_; }
  /// World inverse inertia R I_body⁻¹ Rᵀ (zero for a particle).
  Mat3 inverse_inertia_world() const;
  Vec3 angular_velocity() const { return inverse_inertia_world() * state.L; }
  /// Kinetic (linear + rotational) plus gravitational potential energy, zero at x = 0.
  double energy(const Vec3& gravity) const;
  /// The same, given the angular velocity (angular_velocity(), already computed).
  double energy(const Vec3& gravity, const Vec3& omega) const;

 private:
  std::string name_;
  bool particle_;
  ShapeKind shape_;
  bool fixed_;
  double radius_;
  /// The polyhedron in the body frame, shared by every copy of the body: a world is copied at
  /// every sample, and copying a thousand bodies' corners and faces cost more than their step.
  struct Geometry {
    std::vector<HullFace> faces;
    std::vector<Vec3> edge_directions;
    std::vector<Vec3> vertices;
  };
  static std::shared_ptr<const Geometry> make_geometry(const BodyDef& def);
  std::shared_ptr<const Geometry> geometry_;
  double bounding_radius_;
  Vec3 half_extent_body_;
  double mass_, inverse_mass_;
  Vec3 inertia_body_, inverse_inertia_body_;
  double restitution_;
  Quat principal_axes_;
  Vec3 com_offset_;
  bool identity_axes_;  // no rotation at all is applied (keeps boxes' quaternions bit-exact)
};

}  // namespace tumble
