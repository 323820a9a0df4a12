#pragma once
// The error of an output that the file system refused: the path and the reason (exit 3).
// Private to src/output.

#include <filesystem>
#include <string>

#include "tumble/error.hpp"

namespace tumble {

[[noreturn]] inline void cannot_write(const std::filesystem::path& path, const std::string& why) {
  throw Error(ErrorKind::Environment, "cannot write \"" + path.string() + "\": " + why);
}

}  // namespace tumble
