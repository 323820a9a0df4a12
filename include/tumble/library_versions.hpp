#pragma once
/// The versions of the libraries tumble runs with (`tumble --version`, bug reports). Each layer
/// reports the libraries it owns, from the layer's own source file; src/cli collects them. A shared
/// library reports the version loaded at run time, and the one tumble was built against when that
/// differs; a header-only library reports the version compiled in. The GL driver needs a context:
/// `tumble info` reports it.

#include <string>
#include <vector>

namespace tumble {

struct LibraryVersion {
  std::string name;     ///< e.g. "libavcodec"
  std::string version;  ///< e.g. "59.37.100", or "59.37.100 (built with 59.39.100)"
};
using LibraryVersions = std::vector<LibraryVersion>;

/// "RUNTIME", or "RUNTIME (built with BUILT)" when the two differ.
inline std::string runtime_version(const std::string& runtime, const std::string& built) {
  return runtime == built ? runtime : runtime + " (built with " + built + ")";
}

namespace sim {
LibraryVersions library_versions();  ///< Eigen (src/sim)
}
namespace mesh {
LibraryVersions library_versions();  ///< assimp, Qhull (src/mesh)
}
namespace scene {
LibraryVersions library_versions();  ///< toml++ (src/scene)
}
namespace output {
LibraryVersions library_versions();  ///< OpenSSL libcrypto, nlohmann_json (src/output)
}
namespace video {
LibraryVersions library_versions();  ///< FFmpeg's libavcodec, libavformat, libavfilter, libswscale, libavutil; libpng (src/video)
}

}  // namespace tumble
