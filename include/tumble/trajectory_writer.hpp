#pragma once
/// trajectory.csv: one row per body per sample,
/// `t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,energy`, every float printed in its shortest form
/// that reads back bit-exact (std::to_chars). Written atomically.

#include <filesystem>
#include <string>

#include "tumble/atomic_file.hpp"
#include "tumble/world.hpp"

namespace tumble {

inline constexpr const char* kTrajectoryHeader =
    "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,energy";

class TrajectoryWriter {
 public:
  explicit TrajectoryWriter(const std::filesystem::path& path);
  /// Appends one row per body of `world`, stamped with time t.
  void write(double t, const World& world);
  void commit() { file_.commit(); }
  long rows() const { return rows_; }

 private:
  AtomicFile file_;
  std::string line_;
  long rows_ = 0;
};

/// Shortest decimal form of x that parses back to the same double.
std::string format_double(double x);

}  // namespace tumble
