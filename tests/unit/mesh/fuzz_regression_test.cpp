// Every input fuzz/fuzz_mesh found that crashed, hung or aborted (in tumble or in assimp) is
// kept in data/fuzz/ and must now be refused with a tumble::Error, under every repair mode.
#include <gtest/gtest.h>

#include <algorithm>

#include "mesh_fixtures.hpp"

namespace tumble {
namespace {

TEST(FuzzRegressions, EveryFoundInputIsRefusedCleanly) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(test::kData / "fuzz"))
    files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty());
  for (const auto& file : files)
    for (MeshRepair repair : {MeshRepair::None, MeshRepair::Orient, MeshRepair::Hull}) {
      SCOPED_TRACE(file.filename().string() + ", repair " +
                   std::to_string(static_cast<int>(repair)));
      MeshLoadOptions options;
      options.repair = repair;
      EXPECT_THROW(load_mesh_body(file, options), Error);
    }
}

}  // namespace
}  // namespace tumble
