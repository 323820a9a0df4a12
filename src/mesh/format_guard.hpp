#pragma once
// Checks run on a model's bytes before assimp sees them, for inputs that Debian's assimp 5.2.5
// is known (from fuzzing, fuzz/) to hang or crash on. Each guard refuses what the format's
// specification does not allow, with a clear message, and lets everything valid through.

#include <filesystem>
#include <string>

namespace tumble::mesh_detail {

/// "" when `file` (with lower-case extension `extension`) may go to assimp, else what is wrong.
std::string guard_format(const std::filesystem::path& file, const std::string& extension);

}  // namespace tumble::mesh_detail
