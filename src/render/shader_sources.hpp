#pragma once
// GLSL sources from shaders/, embedded into the binary at build time (CMake generates
// shader_sources.cpp), so the installed binary runs from any folder.

#include <string_view>

namespace tumble {

/// The text of shaders/<name>; aborts (assert) on an unknown name, a programming error.
std::string_view shader_source(std::string_view name);

}  // namespace tumble
