#pragma once
// A fresh, empty folder under the system temp dir for one unit test, named
// tumble_<suite>_<name>; tests that write files use it instead of the working folder.

#include <filesystem>
#include <string>

namespace tumble::test {

inline std::filesystem::path fresh_dir(const std::string& suite, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tumble_" + suite + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace tumble::test
