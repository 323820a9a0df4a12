#include "mesh_error.hpp"

#include <cstdio>

#include "tumble/error.hpp"

namespace tumble::mesh_detail {

void throw_mesh_error(const std::filesystem::path& file, const std::string& message) {
  throw Error(ErrorKind::BadInput, message, SourceLocation{file.string()});
}

std::string format_number(double x) {
  if (x == 0.0) x = 0.0;  // prints -0 as 0
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

std::string format_point(const Vec3& p) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on a chain of operator+.
  std::string s = "(";
  s += format_number(p.x());
  s += ", ";
  s += format_number(p.y());
  s += ", ";
  s += format_number(p.z());
  s += ")";
  return s;
}

std::string count_of(std::size_t n, const std::string& singular, const std::string& plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

}  // namespace tumble::mesh_detail
