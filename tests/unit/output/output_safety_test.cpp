// The output layer under odd paths and concurrency (issue 19): what a path names decides how an
// output gets there (replaced, written through, refused), temporary names are unique, one run
// at a time per folder, and a run's outputs are committed together or not at all.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <future>
#include <sstream>
#include <thread>

#include "../test_dir.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/error.hpp"
#include "tumble/folder_lock.hpp"
#include "tumble/output_folder.hpp"
#include "tumble/output_target.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  return test::fresh_dir("output_safety_test", name);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

bool is_char_device(const fs::path& p) {
  struct stat st {};
  return stat(p.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

// A character device that behaves as /dev/null (1, 3), made in the test's own folder: the
// machine's /dev is never touched. Only root may make one.
bool make_null_device(const fs::path& p) {
  return mknod(p.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
}

#define SKIP_UNLESS_ROOT()                                                                \
  do {                                                                                    \
    if (geteuid() != 0) GTEST_SKIP() << "needs root to mknod a device (CI runs as root)"; \
  } while (0)

int exit_code_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.exit_code();
  }
  return 0;
}

// ----------------------------------------------------------------------------------------------
// What a path names

TEST(OutputTarget, AMissingParentFolderIsExit3AndIsNotCreated) {
  const fs::path dir = fresh_dir("missing_parent");
  try {
    write_file_atomically(dir / "absent/x.png", "png");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 3);
    EXPECT_NE(std::string(e.what()).find("absent/x.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "absent"));
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(OutputTarget, AFolderInThePlaceOfTheFileIsExit3) {
  const fs::path dir = fresh_dir("folder_in_place");
  fs::create_directory(dir / "x.png");
  EXPECT_EQ(exit_code_of([&] { write_file_atomically(dir / "x.png", "png"); }), 3);
  EXPECT_TRUE(fs::is_directory(dir / "x.png"));
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"x.png"});
}

TEST(OutputTarget, ACharacterDeviceIsWrittenThroughNeverReplaced) {
  SKIP_UNLESS_ROOT();
  const fs::path dir = fresh_dir("device");
  ASSERT_TRUE(make_null_device(dir / "null"));
  EXPECT_EQ(output_target(dir / "null").kind, OutputTarget::Kind::WriteThrough);
  write_file_atomically(dir / "null", std::string(100000, 'x'));
  EXPECT_TRUE(is_char_device(dir / "null")) << "the device was replaced by a file";
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"null"}) << "a temporary was left";
}

TEST(OutputTarget, ASymlinkToADeviceIsFollowedAndStays) {
  SKIP_UNLESS_ROOT();
  const fs::path dir = fresh_dir("device_link");
  ASSERT_TRUE(make_null_device(dir / "null"));
  fs::create_symlink("null", dir / "link");
  write_file_atomically(dir / "link", "bytes");
  EXPECT_TRUE(fs::is_symlink(dir / "link"));
  EXPECT_EQ(fs::read_symlink(dir / "link"), fs::path("null"));
  EXPECT_TRUE(is_char_device(dir / "null"));
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"link", "null"}));
}

TEST(OutputTarget, AFifoGetsTheBytesAndStaysAFifo) {
  const fs::path dir = fresh_dir("fifo");
  ASSERT_EQ(mkfifo((dir / "pipe").c_str(), 0666), 0);
  const std::string bytes(200000, 'q');  // more than a pipe's buffer: the reader must drain it
  // Held open for writing by the test as well, so that the reader never blocks on a FIFO that a
  // broken writer replaced; let go once the write is done, so the reader sees the end.
  const int holder = open((dir / "pipe").c_str(), O_RDWR | O_CLOEXEC);
  ASSERT_GE(holder, 0);
  auto reader = std::async(std::launch::async, [&] { return slurp(dir / "pipe"); });
  write_file_atomically(dir / "pipe", bytes);
  close(holder);
  EXPECT_EQ(reader.get(), bytes);
  struct stat st {};
  ASSERT_EQ(lstat((dir / "pipe").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"pipe"});
}

TEST(OutputTarget, ASymlinkToAFileKeepsTheLinkAndReplacesWhatItNames) {
  const fs::path dir = fresh_dir("file_link");
  fs::create_directory(dir / "elsewhere");
  std::ofstream(dir / "elsewhere/real.txt") << "old";
  fs::create_symlink("elsewhere/real.txt", dir / "link.txt");
  write_file_atomically(dir / "link.txt", "new");
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(slurp(dir / "elsewhere/real.txt"), "new");
  EXPECT_EQ(names_in(dir / "elsewhere"), std::vector<std::string>{"real.txt"});
}

// ----------------------------------------------------------------------------------------------
// Temporary names

TEST(AtomicFile, TwoWritersOfOnePathHaveTheirOwnTemporaries) {
  const fs::path dir = fresh_dir("two_writers");
  const fs::path target = dir / "trajectory.csv";
  AtomicFile a(target), b(target);
  EXPECT_NE(a.temporary_path(), b.temporary_path());
  for (const AtomicFile* f : {&a, &b}) {
    const std::string name = f->temporary_path().filename().string();
    EXPECT_TRUE(name.starts_with(".trajectory.csv.") && name.ends_with(".partial")) << name;
    EXPECT_EQ(f->temporary_path().parent_path(), dir);
  }
  // Interleaved writes: neither sees the other's bytes, and the last commit wins whole.
  for (int i = 0; i < 1000; ++i) {
    a.write("a,1\n");
    b.write("b,2\n");
  }
  b.commit();
  a.commit();
  std::string expected;
  for (int i = 0; i < 1000; ++i) expected += "a,1\n";
  EXPECT_EQ(slurp(target), expected);
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"trajectory.csv"});
}

TEST(AtomicFile, ANewFileGetsTheUsualPermissions) {
  // mkstemp makes 0600 files; an output is as readable as any other file the user makes.
  const fs::path dir = fresh_dir("mode");
  const mode_t mask = umask(022);
  write_file_atomically(dir / "a.txt", "x");
  umask(mask);
  EXPECT_EQ(fs::status(dir / "a.txt").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                fs::perms::others_read);
}

// ----------------------------------------------------------------------------------------------
// One run at a time per folder

TEST(FolderLock, ASecondHolderFailsAtOnceNamingTheFolder) {
  const fs::path dir = fresh_dir("lock_twice");
  const FolderLock first(dir);
  EXPECT_TRUE(fs::exists(dir / FolderLock::kFileName));
  try {
    const FolderLock second(dir);
    FAIL() << "two locks on one folder";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 3);
    const std::string what = e.what();
    EXPECT_NE(what.find("\"" + dir.string() + "\""), std::string::npos) << what;
    EXPECT_NE(what.find("another tumble run"), std::string::npos) << what;
    EXPECT_NE(what.find("is writing it"), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(getpid())), std::string::npos) << "no process id: " << what;
  }
}

TEST(FolderLock, ReleasedItLeavesNoFileAndCanBeTakenAgain) {
  const fs::path dir = fresh_dir("lock_again");
  { const FolderLock lock(dir); }
  EXPECT_TRUE(fs::is_empty(dir));
  const FolderLock again(dir);
  EXPECT_TRUE(fs::exists(dir / FolderLock::kFileName));
}

TEST(FolderLock, ADeadHolderBlocksNoOne) {
  // A holder killed outright (no destructor runs, the file stays): the kernel drops its lock.
  const fs::path dir = fresh_dir("lock_dead");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    try {
      new FolderLock(dir);  // never released: the process dies holding it
    } catch (...) {
      _exit(2);
    }
    raise(SIGKILL);
    _exit(1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the child failed to take the lock";
  EXPECT_TRUE(fs::exists(dir / FolderLock::kFileName)) << "the dead holder's file stays";
  EXPECT_NO_THROW(FolderLock{dir});
}

// ----------------------------------------------------------------------------------------------
// A run's outputs as one set

bool is_frame(const std::string& name) {
  return name.starts_with("frame_") && name.ends_with(".png");
}

TEST(OutputFolder, NothingAppearsBeforeCommitAndEverythingAfter) {
  const fs::path dir = fresh_dir("set") / "o";
  {
    OutputFolder out(dir);
    const StagedOutput clip = out.file("clip.mp4");
    const StagedOutput frames = out.folder("frames", is_frame);
    EXPECT_EQ(clip.final, dir / "clip.mp4");
    EXPECT_NE(clip.staged, clip.final);
    EXPECT_TRUE(fs::is_directory(frames.staged));
    write_file_atomically(clip.staged, "clip");
    write_file_atomically(frames.staged / "frame_00000.png", "f0");
    EXPECT_EQ(out.staged_path_of(dir / "frames/frame_00000.png"),
              frames.staged / "frame_00000.png");
    write_file_atomically(out.file("run.json").staged, "{}");
    EXPECT_FALSE(fs::exists(dir / "clip.mp4"));
    EXPECT_FALSE(fs::exists(dir / "run.json"));
    out.commit();
  }
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"clip.mp4", "frames", "run.json"}));
  EXPECT_EQ(slurp(dir / "clip.mp4"), "clip");
  EXPECT_EQ(names_in(dir / "frames"), std::vector<std::string>{"frame_00000.png"});
}

TEST(OutputFolder, DestroyedWithoutCommitTheFolderIsAsItWas) {
  const fs::path dir = fresh_dir("abandoned");
  std::ofstream(dir / "clip.mp4") << "old clip";
  {
    OutputFolder out(dir);
    write_file_atomically(out.file("clip.mp4").staged, "new clip");
    write_file_atomically(out.folder("frames", is_frame).staged / "frame_00000.png", "f");
    // an exception unwinds here
  }
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"clip.mp4"});
  EXPECT_EQ(slurp(dir / "clip.mp4"), "old clip");
}

TEST(OutputFolder, AFolderOutputReplacesThePreviousOneWhole) {
  const fs::path dir = fresh_dir("fewer_frames");
  for (const int frames : {5, 2}) {
    OutputFolder out(dir);
    const StagedOutput f = out.folder("frames", is_frame);
    for (int k = 0; k < frames; ++k)
      write_file_atomically(f.staged / ("frame_0000" + std::to_string(k) + ".png"),
                            std::to_string(frames));
    out.commit();
  }
  EXPECT_EQ(names_in(dir / "frames"),
            (std::vector<std::string>{"frame_00000.png", "frame_00001.png"}));
  EXPECT_EQ(slurp(dir / "frames/frame_00001.png"), "2");
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"frames"});
}

TEST(OutputFolder, AFolderOutputHoldingOtherFilesIsRefusedNotReplaced) {
  const fs::path dir = fresh_dir("foreign");
  fs::create_directories(dir / "frames");
  std::ofstream(dir / "frames/frame_00000.png") << "old";
  std::ofstream(dir / "frames/notes.txt") << "mine";
  OutputFolder out(dir);
  try {
    out.folder("frames", is_frame);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 3);
    EXPECT_NE(std::string(e.what()).find("notes.txt"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(dir / "frames/notes.txt"), "mine");
}

TEST(OutputFolder, ADeadRunsStagingIsClearedByTheNextRun) {
  const fs::path dir = fresh_dir("dead_staging");
  fs::create_directories(dir / ".tumble-run.AbC123.partial/frames");
  std::ofstream(dir / ".tumble-run.AbC123.partial/frames/frame_00000.png") << "x";
  std::ofstream(dir / "keep.txt") << "not tumble's";
  { const OutputFolder out(dir); }
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"keep.txt"});
}

TEST(OutputFolder, ErrorsNameTheFinalPaths) {
  const fs::path dir = fresh_dir("names");
  OutputFolder out(dir);
  const StagedOutput s = out.file("still_1.png");
  const Error e(ErrorKind::Environment, "cannot write \"" + s.staged.string() + "\": full");
  EXPECT_EQ(std::string(out.in_final_names(e).what()),
            "cannot write \"" + (dir / "still_1.png").string() + "\": full");
  EXPECT_EQ(out.in_final_names(e).exit_code(), 3);
}

}  // namespace
}  // namespace tumble
