// libFuzzer target: bytes -> tumble::parse_scene. Any text must either parse into a Scene or
// be refused with a tumble::Error; any other exception, crash or sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tumble/error.hpp"
#include "tumble/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    tumble::parse_scene(text, "fuzz.toml");
  } catch (const tumble::Error&) {
  }
  return 0;
}
