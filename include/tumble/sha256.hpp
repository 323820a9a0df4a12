#pragma once
/// SHA-256 (FIPS 180-4) of bytes and of files, as lowercase hex: run.json names every input and
/// output by its digest so a run can be checked byte for byte. Computed by OpenSSL's libcrypto.

#include <filesystem>
#include <string>
#include <string_view>

namespace tumble {

/// Throws tumble::Error (Environment) only if libcrypto fails (allocation).
std::string sha256_hex(std::string_view bytes);
/// Reads the file in chunks (any size); throws tumble::Error (Environment) when it cannot be read.
std::string sha256_file_hex(const std::filesystem::path& path);

}  // namespace tumble
