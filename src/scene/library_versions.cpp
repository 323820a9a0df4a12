// The scene layer's library: toml++. Debian builds it as a shared library but it has no run-time
// version query, so this is the version of the headers compiled in (the ABI is versioned by them).
#include "tumble/library_versions.hpp"

#include <toml++/toml.h>

namespace tumble::scene {

LibraryVersions library_versions() {
  return {{"toml++", std::to_string(TOML_LIB_MAJOR) + "." + std::to_string(TOML_LIB_MINOR) + "." +
                         std::to_string(TOML_LIB_PATCH)}};
}

}  // namespace tumble::scene
