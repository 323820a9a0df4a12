#pragma once
/// Math vocabulary: Eigen fixed-size types, doubles throughout.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble {

using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// The seed's a* : the matrix with star(a) * b == a.cross(b).
inline Mat3 star(const Vec3& a) {
  Mat3 m;
  m << 0.0, -a.z(), a.y(),  //
      a.z(), 0.0, -a.x(),   //
      -a.y(), a.x(), 0.0;
  return m;
}

constexpr double kPi = 3.14159265358979323846;
inline double radians(double degrees) {
  return degrees * (kPi / 180.0);
}

}  // namespace tumble
