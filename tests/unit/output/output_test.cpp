#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "../test_dir.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/csv_field.hpp"
#include "tumble/error.hpp"
#include "tumble/sha256.hpp"
#include "tumble/trajectory_writer.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  return test::fresh_dir("output_test", name);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Sha256, MatchesFipsVectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // FIPS 180-2 / NIST CSHA 896-bit message: two 64-byte blocks plus padding into a third.
  EXPECT_EQ(sha256_hex("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmno"
                       "ijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu"),
            "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
}

// Files are digested in 64 KiB chunks: the NIST million-'a' vector spans 16 chunks, the last one
// partial, so this checks that chunks are streamed into one digest (exact: digests are equal or
// not).
TEST(Sha256, StreamsAFileInChunksToTheNistDigest) {
  const fs::path dir = fresh_dir("sha_stream");
  {
    std::ofstream(dir / "million_a", std::ios::binary) << std::string(1000000, 'a');
    std::ofstream(dir / "empty", std::ios::binary);
  }
  EXPECT_EQ(sha256_file_hex(dir / "million_a"),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  EXPECT_EQ(sha256_file_hex(dir / "empty"),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  // A size that ends exactly on a chunk boundary, with every byte value: same as the one-shot
  // digest.
  std::string bytes(3 * 65536, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 131 % 256);
  std::ofstream(dir / "boundary", std::ios::binary) << bytes;
  EXPECT_EQ(sha256_file_hex(dir / "boundary"), sha256_hex(bytes));
}

TEST(Sha256, AMissingFileIsAnEnvironmentError) {
  try {
    sha256_file_hex(fresh_dir("sha_missing") / "absent");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Environment);
  }
}

TEST(AtomicFile, AppearsOnlyOnCommit) {
  const fs::path dir = fresh_dir("commit");
  const fs::path target = dir / "a.txt";
  {
    AtomicFile f(target);
    f.write("hello");
    EXPECT_FALSE(fs::exists(target));
    EXPECT_TRUE(fs::exists(f.temporary_path()));
    f.commit();
  }
  EXPECT_EQ(slurp(target), "hello");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, AbandonedWriteKeepsThePreviousGoodFile) {
  const fs::path dir = fresh_dir("abandon");
  const fs::path target = dir / "a.txt";
  write_file_atomically(target, "good");
  {
    AtomicFile f(target);
    f.write("half-writ");
    // destroyed without commit, as when an exception unwinds
  }
  EXPECT_EQ(slurp(target), "good");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, UnwritableFolderIsAnEnvironmentError) {
  try {
    AtomicFile f("/proc/tumble-cannot-write-here/a.txt");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 3);
    EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos);
  }
}

TEST(FormatDouble, ReadsBackBitExact) {
  for (double x : {0.1, 1.0 / 3.0, -9.81, 1e-300, 6.02214076e23, 0.0, -0.0, 4.9e-324}) {
    const std::string s = format_double(x);
    const double back = std::strtod(s.c_str(), nullptr);
    EXPECT_EQ(std::memcmp(&x, &back, sizeof x), 0) << s;
  }
  EXPECT_EQ(format_double(0.5), "0.5");
}

TEST(CsvField, QuotesOnlyWhatMustBe) {
  EXPECT_EQ(csv_field("box"), "box");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), R"("say ""hi""")");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field(""), "");
}

TEST(TrajectoryWriter, ABodyNameWithACommaKeepsTheColumns) {
  // Scene names are free text: one with a comma, a quote and a line break is one quoted field,
  // so every row still has the header's 16 columns.
  WorldDef def;
  BodyDef b;
  b.name = "a,\"b\"\nc";
  b.particle = true;
  b.mass_kg = 1.0;
  def.bodies.push_back(b);
  const World w(def);
  const fs::path dir = fresh_dir("trajectory_quoting");
  TrajectoryWriter csv(dir / "trajectory.csv");
  csv.write(0.0, w);
  csv.commit();
  const std::string text = slurp(dir / "trajectory.csv");
  EXPECT_NE(text.find("\n0,\"a,\"\"b\"\"\nc\",0,"), std::string::npos) << text;
}

}  // namespace
}  // namespace tumble
