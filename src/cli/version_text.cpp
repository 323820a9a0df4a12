#include "version_text.hpp"

#include <CLI/Version.hpp>

#include "tumble/library_versions.hpp"

namespace tumble::cli {

std::string version_text() {
  std::string text = std::string("tumble ") + TUMBLE_VERSION;
  // Layer by layer, bottom up, as docs/architecture.md lists them; CLI11 is this layer's own.
  for (const LibraryVersions& layer :
       {sim::library_versions(), mesh::library_versions(), scene::library_versions(),
        output::library_versions(), video::library_versions(),
        LibraryVersions{{"CLI11", CLI11_VERSION}}})
    for (const LibraryVersion& library : layer) text += "\n" + library.name + " " + library.version;
  return text;
}

}  // namespace tumble::cli
