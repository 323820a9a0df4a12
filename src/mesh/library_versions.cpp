// The mesh layer's libraries: assimp (its run-time version functions) and Qhull (its version
// string, e.g. "2020.2.r 2020/08/31").
#include "tumble/library_versions.hpp"

#include <assimp/version.h>
#include <libqhull_r/libqhull_r.h>

namespace tumble::mesh {

LibraryVersions library_versions() {
  const std::string assimp = std::to_string(aiGetVersionMajor()) + "." +
                             std::to_string(aiGetVersionMinor()) + "." +
                             std::to_string(aiGetVersionPatch());
  return {{"assimp", assimp}, {"Qhull", qh_version}};
}

}  // namespace tumble::mesh
