#pragma once
// How the mesh layer reports a bad model: a tumble::Error (BadInput, exit 2) whose location is
// the file, so that it reads "FILE: problem", and points printed the way users see them.

#include <filesystem>
#include <string>

#include "tumble/math.hpp"

namespace tumble::mesh_detail {

/// Throws tumble::Error(BadInput, message, {file}).
[[noreturn]] void throw_mesh_error(const std::filesystem::path& file, const std::string& message);

/// "(0.5, 0, 1)": six significant digits, no "-0".
std::string format_point(const Vec3& p);
/// A number with six significant digits ("0.001", "1.5e+06").
std::string format_number(double x);
/// "1 open edge" / "12 open edges".
std::string count_of(std::size_t n, const std::string& singular, const std::string& plural);

}  // namespace tumble::mesh_detail
