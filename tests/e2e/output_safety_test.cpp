// Nothing clobbered, nothing mixed, nothing stale (issue 19; docs/outputs.md): output paths that
// name devices, FIFOs and links, a missing folder; two runs into one folder; --png frame sets
// that are interrupted, diverge or fill the disk; run.json as the manifest; SIGHUP and SIGQUIT.
//
// Runs that must be stopped part-way are signalled only once they have demonstrably started (a
// staged frame or file exists), never after a fixed delay, so a loaded machine does not make
// them flaky. Hazards that need root (a device node, a tiny file system) are made by the test in
// its own folder and skipped, with the reason, elsewhere.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <cstring>
#include <functional>
#include <future>
#include <map>
#include <thread>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

using namespace std::chrono_literals;

const std::vector<std::string> kTiny = {"--size", "64x48", "--quiet"};

std::vector<std::string> args(std::vector<std::string> a, const std::vector<std::string>& more) {
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// ---------------------------------------------------------------------------------------------
// A tumble running in the background, and what it leaves.

struct Child {
  pid_t pid = -1;
  fs::path out, err;
};

// Starts tumble (or `env ... tumble` for a sweep) with stdout and stderr into files beside `cwd`.
Child spawn(const std::vector<std::string>& argv_in, const fs::path& cwd, const std::string& tag) {
  Child c;
  c.out = cwd / (tag + ".stdout");
  c.err = cwd / (tag + ".stderr");
  std::vector<std::string> storage = argv_in;
  std::vector<char*> argv;
  for (std::string& a : storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string dir = cwd.string(), out = c.out.string(), err = c.err.string();
  std::fflush(nullptr);
  c.pid = fork();
  if (c.pid == 0) {
    const int in = open("/dev/null", O_RDONLY);
    const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || o < 0 || e < 0 || dup2(in, 0) < 0 || dup2(o, 1) < 0 || dup2(e, 2) < 0) _exit(126);
    if (chdir(dir.c_str()) != 0) _exit(126);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  return c;
}

Child spawn_tumble(const std::vector<std::string>& a, const fs::path& cwd, const std::string& tag) {
  return spawn(args({tumble_binary().string()}, a), cwd, tag);
}

// Waits for the child (killed after `timeout`).
RunResult wait_for(const Child& c, std::chrono::seconds timeout = 300s) {
  RunResult r;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(c.pid, &status, WNOHANG);
    if (done == c.pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      kill(c.pid, SIGKILL);
      waitpid(c.pid, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(10ms);
  }
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  r.out = read_file(c.out);
  r.err = read_file(c.err);
  return r;
}

// Polls `condition` until it holds (true) or `timeout` passes (false).
bool eventually(const std::function<bool()>& condition, std::chrono::seconds timeout = 120s) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return false;
}

// The staging folders of runs writing into `dir` (.tumble-run.XXXXXX.partial).
std::vector<fs::path> staging_folders(const fs::path& dir) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with(".tumble-run.") && name.ends_with(".partial")) found.push_back(it->path());
  }
  return found;
}

// Whether a run writing into `dir` has staged `relative` (e.g. "frames/frame_00002.png").
bool staged(const fs::path& dir, const fs::path& relative) {
  for (const fs::path& s : staging_folders(dir))
    if (fs::exists(s / relative)) return true;
  return false;
}

// Whether a run writing into `dir` has staged anything at all (the clip's temporary).
bool staged_anything(const fs::path& dir) {
  for (const fs::path& s : staging_folders(dir))
    if (!fs::is_empty(s)) return true;
  return false;
}

// Every regular file under `dir` (its relative path) with its bytes: "exactly as before".
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return files;
}

// Names of the entries of `dir` in its snapshot, for a short assertion message.
std::string listing(const std::map<std::string, std::string>& files) {
  std::string s;
  for (const auto& [name, bytes] : files) s += name + " (" + std::to_string(bytes.size()) + ") ";
  return s;
}

// No temporary (.partial) file or folder and no lock file anywhere under `root`.
::testing::AssertionResult nothing_left(const fs::path& root) {
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string name = e.path().filename().string();
    if ((name.front() == '.' && name.ends_with(".partial")) || name == ".tumble.lock")
      return ::testing::AssertionFailure() << "left behind: " << e.path();
  }
  return ::testing::AssertionSuccess();
}

// run.json's outputs: path → sha256.
std::map<std::string, std::string> manifest(const fs::path& run_json) {
  std::map<std::string, std::string> m;
  const nlohmann::json j = read_json(run_json);  // kept: a temporary's member would dangle
  for (const auto& o : j["outputs"])
    m[o["path"].get<std::string>()] = o["sha256"].get<std::string>();
  return m;
}

bool is_root() {
  return geteuid() == 0;
}

bool is_char_device(const fs::path& p) {
  struct stat st {};
  return stat(p.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

// A character device that behaves as /dev/null, in the test's own folder (never the machine's
// /dev).
void make_null_device(const fs::path& p) {
  ASSERT_EQ(mknod(p.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0) << std::strerror(errno);
}

#define SKIP_UNLESS_ROOT(what)                                                  \
  do {                                                                          \
    if (!is_root()) GTEST_SKIP() << "needs root to " what " (CI runs as root)"; \
  } while (0)

// A FIFO's whole content, read on another thread (the writer blocks until it is opened).
std::future<std::string> read_fifo_later(const fs::path& fifo) {
  return std::async(std::launch::async, [fifo] { return read_file(fifo); });
}

// A reader of a FIFO that cannot hang the test, whatever the program does to the FIFO (a
// broken one renames a file over it, and a reader blocked on the old FIFO would wait forever):
// the test holds the FIFO open for writing too, so the reader's open never blocks, and lets go
// once the program has ended, so the reader sees the end of the data.
class FifoReader {
 public:
  explicit FifoReader(const fs::path& fifo)
      : holder_(open(fifo.c_str(), O_RDWR | O_CLOEXEC)),
        bytes_(std::async(std::launch::async, [fifo] { return read_file(fifo); })) {}
  ~FifoReader() {
    if (holder_ >= 0) close(holder_);
  }
  FifoReader(const FifoReader&) = delete;
  FifoReader& operator=(const FifoReader&) = delete;
  /// Everything written into the FIFO; call after the writer has ended.
  std::string bytes() {
    close(holder_);
    holder_ = -1;
    return bytes_.get();
  }

 private:
  int holder_;
  std::future<std::string> bytes_;
};

// Two stills of a falling box that differ: the inputs of the diff tests.
void make_two_stills(const TestDir& dir) {
  const RunResult r = run_tumble({"render", "--no-mp4", "--still", "0", "--still", "0.4",
                                  "--duration", "0.5", "--size", "32x24", "--out", "s"},
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
}

// ---------------------------------------------------------------------------------------------
// 1. Output paths behave like ffmpeg's

TEST(OutputPaths, DiffOutOntoADeviceOrALinkToItDiscardsAndKeepsTheDevice) {
  SKIP_UNLESS_ROOT("mknod a device");
  const TestDir dir;
  make_two_stills(dir);
  make_null_device(dir / "null");
  fs::create_symlink("null", dir / "link");
  for (const char* out : {"null", "link"}) {
    SCOPED_TRACE(out);
    const RunResult r =
        run_tumble({"diff", "s/still_0.png", "s/still_0.4.png", "--diff-out", out}, dir.path());
    EXPECT_EQ(r.exit_code, 1) << describe(r);
    EXPECT_NE(r.out.find(std::string("diff image ") + out), std::string::npos) << r.out;
    EXPECT_TRUE(is_char_device(dir / "null")) << "the device was replaced";
    EXPECT_TRUE(fs::is_symlink(dir / "link"));
  }
  EXPECT_TRUE(nothing_left(dir.path()));
}

TEST(OutputPaths, DiffOutIntoAFifoStreamsThePng) {
  const TestDir dir;
  make_two_stills(dir);
  ASSERT_EQ(mkfifo((dir / "pipe").c_str(), 0666), 0);
  FifoReader reader(dir / "pipe");
  const RunResult r =
      run_tumble({"diff", "s/still_0.png", "s/still_0.4.png", "--diff-out", "pipe"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(reader.bytes().starts_with("\x89PNG\r\n\x1a\n")) << "no PNG came through the FIFO";
  struct stat st {};
  ASSERT_EQ(lstat((dir / "pipe").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
  EXPECT_TRUE(nothing_left(dir.path()));
}

TEST(OutputPaths, DiffOutThroughALinkToStdoutStreamsThePng) {
  // What /dev/stdout is (a link to /proc/self/fd/1), made in the test's folder: the machine's
  // own /dev/stdout is not put at risk. Stdout is a pipe here.
  const TestDir dir;
  make_two_stills(dir);
  fs::create_symlink("/proc/self/fd/1", dir / "stdout");
  const RunResult r =
      run_tumble({"diff", "s/still_0.png", "s/still_0.4.png", "--diff-out", "stdout"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(r.out.starts_with("\x89PNG\r\n\x1a\n")) << "no PNG on stdout";
  EXPECT_TRUE(fs::is_symlink(dir / "stdout")) << "the link was replaced";
  EXPECT_TRUE(nothing_left(dir.path()));
}

TEST(OutputPaths, DiffOutInAMissingFolderIsExit3AndCreatesNothing) {
  const TestDir dir;
  make_two_stills(dir);
  const RunResult r = run_tumble(
      {"diff", "s/still_0.png", "s/still_0.4.png", "--diff-out", "nonexistent/x.png"}, dir.path());
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: cannot write \"nonexistent/x.png\"")) << r.err;
  EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "nonexistent"));
}

TEST(OutputPaths, RenderOutputsThatAreLinksKeepThem) {
  // o/clip.mp4 links to a device: written through; o/still_0.2.png links to a file elsewhere:
  // the link stays and the file it names gets the still.
  SKIP_UNLESS_ROOT("mknod a device");
  const TestDir dir;
  make_null_device(dir / "null");
  fs::create_directories(dir / "o");
  fs::create_directories(dir / "kept");
  fs::create_symlink("../null", dir / "o/clip.mp4");
  fs::create_symlink("../kept/still.png", dir / "o/still_0.2.png");
  const RunResult r = run_tumble(
      args({"render", "--duration", "0.25", "--still", "0.2", "--out", "o"}, kTiny), dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(is_char_device(dir / "null"));
  EXPECT_TRUE(fs::is_symlink(dir / "o/clip.mp4"));
  EXPECT_TRUE(fs::is_symlink(dir / "o/still_0.2.png"));
  EXPECT_TRUE(read_file(dir / "kept/still.png").starts_with("\x89PNG"));
  const auto m = manifest(dir / "o/run.json");
  EXPECT_EQ(m.size(), 2u);
  EXPECT_EQ(m.at("o/still_0.2.png"), system_sha256(dir / "kept/still.png"));
  EXPECT_TRUE(m.count("o/clip.mp4"));
  EXPECT_TRUE(nothing_left(dir.path()));
}

// ---------------------------------------------------------------------------------------------
// 2. One run at a time per output folder

// The first run is held at its commit by a FIFO among its outputs (it writes through into it
// only once a reader opens it), so the second run certainly meets a live first run.
TEST(Concurrency, ASecondSimulateIntoABusyFolderFailsAtOnceAndTheFirstStaysWhole) {
  const TestDir dir;
  write_scene(dir.path(), "a.toml", kDropScene);
  write_scene(dir.path(), "b.toml", replace(std::string(kDropScene), "\"box\"", "\"other\""));
  fs::create_directories(dir / "o");
  ASSERT_EQ(mkfifo((dir / "o/trajectory.svg").c_str(), 0666), 0);
  const Child first =
      spawn_tumble({"simulate", "a.toml", "--out", "o", "--plot", "--quiet"}, dir.path(), "a");
  // trajectory.csv is committed before trajectory.svg: the first run is in its commit.
  const bool committing = eventually([&] { return fs::exists(dir / "o/trajectory.csv"); });
  if (!committing) kill(first.pid, SIGKILL);
  ASSERT_TRUE(committing) << describe(wait_for(first));

  const auto t0 = std::chrono::steady_clock::now();
  const RunResult second = run_tumble({"simulate", "b.toml", "--out", "o"}, dir.path());
  const double second_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(second.exit_code, 3) << describe(second);
  EXPECT_TRUE(
      second.err.starts_with("tumble: error: the output folder \"o\" is in use: another "
                             "tumble run (process " +
                             std::to_string(first.pid) + ") is writing it"))
      << second.err;
  EXPECT_LT(second_s, 30.0) << "the second run did not fail at once";

  std::future<std::string> svg = read_fifo_later(dir / "o/trajectory.svg");
  const RunResult a = wait_for(first);
  ASSERT_EQ(a.exit_code, 0) << describe(a);
  ASSERT_EQ(svg.wait_for(60s), std::future_status::ready);
  const std::string svg_bytes = svg.get();
  EXPECT_NE(svg_bytes.find("<svg"), std::string::npos);
  // The first run's outputs are whole, its own, and match its run.json.
  const Csv csv = read_csv(dir / "o/trajectory.csv");
  ASSERT_EQ(csv.rows.size(), 31u);
  for (const auto& row : csv.rows) EXPECT_EQ(row[1], "box");
  const auto m = manifest(dir / "o/run.json");
  EXPECT_EQ(m.at("o/trajectory.csv"), system_sha256(dir / "o/trajectory.csv"));
  write_file(dir / "svg_copy", svg_bytes);
  EXPECT_EQ(m.at("o/trajectory.svg"), system_sha256(dir / "svg_copy"));
  EXPECT_EQ(read_json(dir / "o/run.json")["scene"]["path"], "a.toml");
  EXPECT_TRUE(nothing_left(dir.path()));
}

TEST(Concurrency, ASecondRenderPngIntoABusyFolderFailsAndTheFramesAreTheFirstsAlone) {
  const TestDir dir;
  fs::create_directories(dir / "o");
  ASSERT_EQ(mkfifo((dir / "o/still_0.1.png").c_str(), 0666), 0);
  // frames/ is committed before the still, which waits for a reader.
  const Child first = spawn_tumble(
      args({"render", "--png", "--no-mp4", "--duration", "0.5", "--still", "0.1", "--out", "o"},
           kTiny),
      dir.path(), "a");
  const bool committing = eventually([&] { return fs::exists(dir / "o/frames"); });
  if (!committing) kill(first.pid, SIGKILL);
  ASSERT_TRUE(committing) << describe(wait_for(first));

  const RunResult second = run_tumble(
      args({"render", "--png", "--no-mp4", "--duration", "0.25", "--fps", "24", "--out", "o"},
           kTiny),
      dir.path());
  EXPECT_EQ(second.exit_code, 3) << describe(second);
  EXPECT_NE(second.err.find("another tumble run"), std::string::npos) << second.err;

  std::future<std::string> still = read_fifo_later(dir / "o/still_0.1.png");
  const RunResult a = wait_for(first);
  ASSERT_EQ(a.exit_code, 0) << describe(a);
  ASSERT_EQ(still.wait_for(60s), std::future_status::ready);
  EXPECT_TRUE(still.get().starts_with("\x89PNG"));
  // Exactly the first run's 30 frames, each as its run.json says.
  const std::vector<std::string> frames = names_in(dir / "o/frames");
  ASSERT_EQ(frames.size(), 30u);
  const auto m = manifest(dir / "o/run.json");
  EXPECT_EQ(m.size(), 31u);
  for (const std::string& f : frames)
    EXPECT_EQ(m.at("o/frames/" + f), system_sha256(dir / "o/frames" / f)) << f;
  EXPECT_TRUE(nothing_left(dir.path()));
}

TEST(Concurrency, ARunKilledOutrightBlocksNoOneAndItsLeftoversGoWithTheNextRun) {
  const TestDir dir;
  const Child killed = spawn_tumble(
      args({"render", "--png", "--no-mp4", "--duration", "10000", "--out", "o"}, kTiny), dir.path(),
      "killed");
  const bool started = eventually([&] { return staged(dir / "o", "frames/frame_00001.png"); });
  kill(killed.pid, SIGKILL);
  const RunResult k = wait_for(killed);
  ASSERT_TRUE(started) << describe(k);
  EXPECT_EQ(k.signal, SIGKILL);
  EXPECT_EQ(staging_folders(dir / "o").size(), 1u) << "SIGKILL cannot be cleaned up after";

  const RunResult next = run_tumble(
      args({"render", "--png", "--no-mp4", "--duration", "0.25", "--out", "o"}, kTiny), dir.path());
  ASSERT_EQ(next.exit_code, 0) << describe(next);
  EXPECT_EQ(names_in(dir / "o/frames").size(), 15u);
  EXPECT_EQ(names_in(dir / "o"), (std::vector<std::string>{"frames", "run.json"}));
  EXPECT_TRUE(nothing_left(dir.path()));
}

// ---------------------------------------------------------------------------------------------
// 3. The --png frame set is one output

// A previous good run: 18 frames at 60 fps (0.3 s), 64x48, and its run.json.
std::map<std::string, std::string> previous_png_run(const TestDir& dir, const fs::path& out) {
  const RunResult good = run_tumble(
      args({"render", "--png", "--no-mp4", "--duration", "0.3", "--out", out.string()}, kTiny),
      dir.path());
  EXPECT_EQ(good.exit_code, 0) << describe(good);
  EXPECT_EQ(names_in(dir / out / "frames").size(), 18u);
  return snapshot(dir / out);
}

TEST(PngFrames, AnInterruptedRunLeavesThePreviousFramesExactly) {
  const TestDir dir;
  const auto before = previous_png_run(dir, "o");
  for (const int signal : {SIGINT, SIGTERM}) {
    SCOPED_TRACE("signal " + std::to_string(signal));
    const Child run = spawn_tumble(
        args({"render", "--png", "--no-mp4", "--duration", "10000", "--out", "o"}, kTiny),
        dir.path(), "stopped");
    // Stopped once it has staged a few new frames of its own.
    const bool started = eventually([&] { return staged(dir / "o", "frames/frame_00003.png"); });
    kill(run.pid, started ? signal : SIGKILL);
    const RunResult r = wait_for(run);
    ASSERT_TRUE(started) << describe(r);
    EXPECT_EQ(r.exit_code, 128 + signal) << describe(r);
    const auto after = snapshot(dir / "o");
    EXPECT_TRUE(after == before) << "before: " << listing(before) << "\nafter: " << listing(after);
    EXPECT_TRUE(nothing_left(dir.path()));
  }
}

TEST(PngFrames, ADivergingRunLeavesThePreviousFramesExactly) {
  // Stiff drag under explicit Euler (c dt / m = 1000): the state stops being finite near
  // t = 0.1 s, after a few frames are staged. The camera is given: no framing run first.
  const TestDir dir;
  const auto before = previous_png_run(dir, "o");
  write_scene(dir.path(), "stiff.toml", R"([simulation]
duration = 1.0
integrator = "euler"
linear_drag = 1000000.0
[camera]
position = [0.0, 1.0, 10.0]
target = [0.0, 0.0, 0.0]
[light]
shadows = false
[[body]]
name = "p"
shape = "particle"
size = [0.1, 0.1, 0.1]
mass = 1.0
velocity = [1.0, 0.0, 0.0]
)");
  const RunResult r = run_tumble(args({"render", "stiff.toml", "--png", "--no-mp4", "--fps", "60",
                                       "--draw-every-frame", "--out", "o"},
                                      kTiny),
                                 dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_NE(r.err.find("stopped being finite"), std::string::npos) << r.err;
  const auto after = snapshot(dir / "o");
  EXPECT_TRUE(after == before) << "before: " << listing(before) << "\nafter: " << listing(after);
  EXPECT_TRUE(nothing_left(dir.path()));
}

// A tmpfs of `size` mounted at `dir` for the test's length.
class SmallDisk {
 public:
  SmallDisk(const fs::path& dir, const std::string& size) : dir_(dir) {
    fs::create_directories(dir);
    mounted_ = mount("tumble-test", dir.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0;
    error_ = mounted_ ? "" : std::strerror(errno);
  }
  ~SmallDisk() {
    if (mounted_) umount2(dir_.c_str(), MNT_DETACH);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  bool mounted() const { return mounted_; }
  const std::string& error() const { return error_; }

 private:
  fs::path dir_;
  bool mounted_ = false;
  std::string error_;
};

TEST(PngFrames, ADiskFullRunLeavesThePreviousFramesExactly) {
  SKIP_UNLESS_ROOT("mount a small tmpfs");
  const TestDir dir;
  const SmallDisk disk(dir / "small", "1m");
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here: " << disk.error();
  const auto before = previous_png_run(dir, "small/o");
  // 60 frames at 640x480 are several MB: the disk fills part-way through the frames.
  const RunResult r = run_tumble({"render", "--png", "--no-mp4", "--duration", "1", "--fps", "60",
                                  "--size", "640x480", "--out", "small/o", "--quiet"},
                                 dir.path());
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: cannot write \"small/o/frames/frame_")) << r.err;
  const auto after = snapshot(dir / "small/o");
  EXPECT_TRUE(after == before) << "before: " << listing(before) << "\nafter: " << listing(after);
  EXPECT_TRUE(nothing_left(dir.path()));
}

TEST(PngFrames, ARerunWithFewerFramesLeavesExactlyItsOwn) {
  const TestDir dir;
  previous_png_run(dir, "o");
  const RunResult r = run_tumble(
      args({"render", "--png", "--no-mp4", "--duration", "0.1", "--out", "o"}, kTiny), dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const std::vector<std::string> expected = {"frame_00000.png", "frame_00001.png",
                                             "frame_00002.png", "frame_00003.png",
                                             "frame_00004.png", "frame_00005.png"};
  EXPECT_EQ(names_in(dir / "o/frames"), expected);
  const auto m = manifest(dir / "o/run.json");
  EXPECT_EQ(m.size(), expected.size());
  for (const std::string& f : expected)
    EXPECT_EQ(m.at("o/frames/" + f), system_sha256(dir / "o/frames" / f));
  // The folder now diffs clean against the same run made afresh.
  const RunResult again = run_tumble(
      args({"render", "--png", "--no-mp4", "--duration", "0.1", "--out", "p"}, kTiny), dir.path());
  ASSERT_EQ(again.exit_code, 0) << describe(again);
  const RunResult d = run_tumble({"diff", "o/frames", "p/frames"}, dir.path());
  EXPECT_EQ(d.exit_code, 0) << describe(d);
}

TEST(PngFrames, ASweepJobStoppedLeavesNoneOfItsOutputs) {
  const TestDir dir;
  write_scene(dir.path(), "drop.toml", kDropScene);
  write_file(dir / "plan.toml", R"(scene = "drop.toml"
command = "render"
args = ["--png", "--no-mp4", "--size", "64x48", "--quiet"]
[grid]
"simulation.duration" = [0.2, 10000.0]
)");
  for (const int signal : {SIGTERM, SIGHUP}) {
    SCOPED_TRACE("signal " + std::to_string(signal));
    fs::remove_all(dir / "out");
    const fs::path job1 = dir / "out/plan/job_00001";
    const Child run =
        spawn({"env", "-u", "SLURM_ARRAY_TASK_ID", "-u", "SLURM_ARRAY_TASK_COUNT", "-u",
               "JOB_COMPLETION_INDEX", tumble_binary().string(), "sweep", "plan.toml"},
              dir.path(), "sweep");
    const bool started = eventually([&] { return staged(job1, "frames/frame_00002.png"); });
    kill(run.pid, started ? signal : SIGKILL);
    const RunResult r = wait_for(run);
    ASSERT_TRUE(started) << describe(r);
    EXPECT_EQ(r.exit_code, 128 + signal) << describe(r);
    EXPECT_TRUE(fs::exists(dir / "out/plan/job_00000/run.json"));
    EXPECT_EQ(names_in(job1), std::vector<std::string>{"scene.toml"});
    EXPECT_TRUE(nothing_left(dir.path()));
  }
}

// ---------------------------------------------------------------------------------------------
// 4. run.json is the manifest

TEST(Manifest, ARerunWithOtherOptionsListsExactlyItsOwnOutputsAndDeletesNothing) {
  const TestDir dir;
  const RunResult first = run_tumble(
      args({"render", "--duration", "0.25", "--strobe", "3", "--gif", "--out", "o"}, kTiny),
      dir.path());
  ASSERT_EQ(first.exit_code, 0) << describe(first);
  const auto earlier = snapshot(dir / "o");
  const RunResult second = run_tumble(
      args({"render", "--no-mp4", "--duration", "0.25", "--still", "0.2", "--out", "o"}, kTiny),
      dir.path());
  ASSERT_EQ(second.exit_code, 0) << describe(second);
  // The earlier run's other outputs stay as they were: this run did not write them.
  for (const char* name : {"clip.mp4", "clip.gif", "strobe.png"})
    EXPECT_TRUE(read_file(dir / "o" / name) == earlier.at(name)) << name << " was changed";
  // run.json lists exactly this run's one output.
  const auto m = manifest(dir / "o/run.json");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m.at("o/still_0.2.png"), system_sha256(dir / "o/still_0.2.png"));
  EXPECT_TRUE(nothing_left(dir.path()));
}

TEST(Manifest, ARunThatCannotWriteItsManifestChangesNoOutput) {
  // The outputs and run.json are committed together: a run whose run.json cannot be written
  // (its name taken by a folder) leaves the clip and frames it would have replaced.
  const TestDir dir;
  const RunResult first =
      run_tumble(args({"render", "--png", "--duration", "0.25", "--out", "o"}, kTiny), dir.path());
  ASSERT_EQ(first.exit_code, 0) << describe(first);
  fs::remove(dir / "o/run.json");
  fs::create_directories(dir / "o/run.json");
  const auto before = snapshot(dir / "o");
  const RunResult second =
      run_tumble(args({"render", "--png", "--duration", "0.5", "--out", "o"}, kTiny), dir.path());
  EXPECT_EQ(second.exit_code, 3) << describe(second);
  EXPECT_TRUE(second.err.starts_with("tumble: error: cannot write \"o/run.json\"")) << second.err;
  EXPECT_TRUE(snapshot(dir / "o") == before) << "an output was replaced without its manifest";
  EXPECT_TRUE(fs::is_directory(dir / "o/run.json"));
  EXPECT_TRUE(nothing_left(dir.path()));
}

// ---------------------------------------------------------------------------------------------
// 5. SIGHUP and SIGQUIT are SIGTERM

TEST(Signals, HangupAndQuitEndARenderCleanlyWith128PlusTheSignal) {
  const TestDir dir;
  const RunResult good = run_tumble(
      args({"render", "--duration", "0.25", "--still", "0.1", "--out", "o"}, kTiny), dir.path());
  ASSERT_EQ(good.exit_code, 0) << describe(good);
  const auto before = snapshot(dir / "o");
  for (const int signal : {SIGHUP, SIGQUIT}) {
    SCOPED_TRACE("signal " + std::to_string(signal));
    const Child run =
        spawn_tumble(args({"render", "--duration", "10000", "--still", "0.1", "--out", "o"}, kTiny),
                     dir.path(), "stopped");
    const bool started = eventually([&] { return staged_anything(dir / "o"); });
    kill(run.pid, started ? signal : SIGKILL);
    const RunResult r = wait_for(run);
    ASSERT_TRUE(started) << describe(r);
    EXPECT_EQ(r.exit_code, 128 + signal) << describe(r);
    EXPECT_EQ(r.err, "tumble: interrupted; outputs left as they were\n");
    EXPECT_TRUE(snapshot(dir / "o") == before);
    EXPECT_TRUE(nothing_left(dir.path()));
  }
}

}  // namespace
}  // namespace tumble_e2e
