#pragma once
// The file access assimp gets while it reads one model: read-only, only the model file and files
// in its folder or below (a glTF's buffers, an OBJ's materials), each at most a size limit. A
// model cannot make tumble read /etc/passwd into its vertices, nor a 10 GB "buffer".

#include <assimp/DefaultIOSystem.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tumble::mesh_detail {

class ConfinedIOSystem : public Assimp::DefaultIOSystem {
 public:
  ConfinedIOSystem(const std::filesystem::path& model_file, std::uintmax_t max_file_bytes);

  bool Exists(const char* file) const override;
  Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;

  /// Why the last refused Open was refused ("" when none was): assimp's own message for a
  /// missing referenced file does not say that tumble refused it.
  const std::string& refusal() const { return refusal_; }

  /// Whether a file whose name ends in `extension` (".mtl") was opened: an OBJ's material
  /// library was read.
  bool opened_with_extension(const std::string& extension) const;

  /// The bytes of `file` (a texture), read under the same rules as the model's own files.
  /// Returns false with `why` set when it may not be read or cannot be.
  bool read_whole(const std::filesystem::path& file, std::vector<std::uint8_t>& bytes,
                  std::string& why);

 private:
  /// "" when `file` may be read, else the reason it may not.
  std::string check(const char* file) const;

  std::filesystem::path model_;   // canonical
  std::filesystem::path folder_;  // canonical folder of the model
  std::uintmax_t max_file_bytes_;
  std::string refusal_;
  std::vector<std::string> opened_;  // every file handed to assimp, as it named them
};

}  // namespace tumble::mesh_detail
