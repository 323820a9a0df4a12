#include "tumble/trajectory_writer.hpp"

#include <charconv>

#include "tumble/csv_field.hpp"

namespace tumble {
namespace {

void append(std::string& line, double x) {
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, x);
  line.append(buf, result.ptr);
}

}  // namespace

std::string format_double(double x) {
  std::string s;
  append(s, x);
  return s;
}

TrajectoryWriter::TrajectoryWriter(const std::filesystem::path& path) : file_(path) {
  file_.write(kTrajectoryHeader);
  file_.write("\n");
}

void TrajectoryWriter::write(double t, const World& world) {
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    const RigidBody& b = world.bodies()[i];
    const Vec3 v = b.velocity(), w = b.angular_velocity();
    const Quat q = b.model_orientation();  // the model's frame, as its file has it
    line_.clear();
    append(line_, t);
    line_ += ',';
    line_ += csv_field(b.name());  // a name may hold a comma, a quote, a line break
    for (double x : {b.state.x.x(), b.state.x.y(), b.state.x.z(), q.w(), q.x(), q.y(), q.z(), v.x(),
                     v.y(), v.z(), w.x(), w.y(), w.z(), world.energy(i)}) {
      line_ += ',';
      append(line_, x);
    }
    line_ += '\n';
    file_.write(line_);
    ++rows_;
  }
}

}  // namespace tumble
