// libFuzzer target: bytes -> a model file -> load_mesh_body. The first byte chooses the format
// (its extension: mesh_file_extensions()[b % count]) and the repair ((b / count) % 3: none,
// orient, hull); the rest is the file. A bad model must come back as tumble::Error and nothing
// else: any other exception, crash, leak or sanitizer report is a bug.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "tumble/error.hpp"
#include "tumble/mesh.hpp"

namespace {

// One folder per fuzzing process, holding only the current input: a model that refers to
// other files finds none.
const std::filesystem::path& input_folder() {
  static const std::filesystem::path folder = [] {
    auto dir =
        std::filesystem::temp_directory_path() / ("tumble_fuzz_mesh_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const auto& extensions = tumble::mesh_file_extensions();
  const std::size_t count = extensions.size();
  const std::filesystem::path file = input_folder() / ("model." + extensions[data[0] % count]);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  tumble::MeshLoadOptions options;
  options.repair = static_cast<tumble::MeshRepair>((data[0] / count) % 3);
  // Small limits keep each run fast; they are checked like the real ones.
  options.max_file_bytes = 1u << 20;
  options.max_triangles = 100'000;
  try {
    const tumble::MeshBody body = tumble::load_mesh_body(file, options);
    // What the loader promises of a body it returns.
    if (!(body.mass.volume > 0.0) || body.hull_vertices.size() < 4 || body.mesh.triangles.empty())
      __builtin_trap();
  } catch (const tumble::Error&) {
  }
  std::filesystem::remove(file);
  return 0;
}
