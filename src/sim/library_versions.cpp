// The sim layer's library: Eigen, header-only, so the version compiled in is the one that runs.
#include "tumble/library_versions.hpp"

#include <Eigen/Core>

namespace tumble::sim {

LibraryVersions library_versions() {
  return {{"Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
                        "." + std::to_string(EIGEN_MINOR_VERSION)}};
}

}  // namespace tumble::sim
