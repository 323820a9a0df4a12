#include "confined_io_system.hpp"

#include <assimp/IOStream.hpp>

#include <algorithm>
#include <cctype>
#include <memory>
#include <string_view>
#include <system_error>

namespace tumble::mesh_detail {

namespace fs = std::filesystem;

ConfinedIOSystem::ConfinedIOSystem(const fs::path& model_file, std::uintmax_t max_file_bytes)
    : max_file_bytes_(max_file_bytes) {
  std::error_code ec;
  // Absolute first: weakly_canonical leaves a relative path relative when none of it exists.
  model_ = fs::weakly_canonical(fs::absolute(model_file, ec), ec);
  folder_ = model_.parent_path();
}

std::string ConfinedIOSystem::check(const char* file) const {
  if (file == nullptr) return "no file name";
  std::error_code ec;
  const fs::path path = fs::weakly_canonical(fs::absolute(fs::path(file), ec), ec);
  if (ec) return "cannot resolve \"" + std::string(file) + "\"";
  if (path != model_) {
    // Inside the model's folder: the relative path from the folder must not climb out of it.
    const fs::path relative = path.lexically_relative(folder_);
    if (relative.empty() || *relative.begin() == "..")
      return "refers to \"" + std::string(file) + "\", outside the model's folder";
  }
  if (!fs::is_regular_file(path, ec)) return "";  // assimp reports a missing file itself
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (!ec && bytes > max_file_bytes_)
    return "refers to \"" + std::string(file) + "\" of " + std::to_string(bytes) +
           " bytes, above the limit of " + std::to_string(max_file_bytes_);
  return "";
}

bool ConfinedIOSystem::Exists(const char* file) const {
  return check(file).empty() && DefaultIOSystem::Exists(file);
}

Assimp::IOStream* ConfinedIOSystem::Open(const char* file, const char* mode) {
  const std::string_view m = mode != nullptr ? mode : "rb";
  if (m.find_first_of("wa+") != std::string_view::npos) {
    refusal_ = "tried to write \"" + std::string(file != nullptr ? file : "") + "\"";
    return nullptr;
  }
  if (std::string why = check(file); !why.empty()) {
    refusal_ = std::move(why);
    return nullptr;
  }
  Assimp::IOStream* stream = DefaultIOSystem::Open(file, mode);
  if (stream != nullptr) opened_.emplace_back(file);
  return stream;
}

bool ConfinedIOSystem::opened_with_extension(const std::string& extension) const {
  return std::any_of(opened_.begin(), opened_.end(), [&](const std::string& name) {
    if (name.size() < extension.size()) return false;
    for (std::size_t i = 0; i < extension.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(name[name.size() - extension.size() + i])) !=
          extension[i])
        return false;
    return true;
  });
}

bool ConfinedIOSystem::read_whole(const fs::path& file, std::vector<std::uint8_t>& bytes,
                                  std::string& why) {
  const std::string name = file.string();
  if (std::string refused = check(name.c_str()); !refused.empty()) {
    why = std::move(refused);
    return false;
  }
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) {
    why = "no such file";
    return false;
  }
  if (!fs::is_regular_file(status)) {
    why = "not a regular file";
    return false;
  }
  std::unique_ptr<Assimp::IOStream> stream(DefaultIOSystem::Open(name.c_str(), "rb"));
  if (!stream) {
    why = "cannot open it for reading";
    return false;
  }
  bytes.resize(stream->FileSize());
  if (!bytes.empty() && stream->Read(bytes.data(), 1, bytes.size()) != bytes.size()) {
    why = "cannot read it";
    return false;
  }
  return true;
}

}  // namespace tumble::mesh_detail
