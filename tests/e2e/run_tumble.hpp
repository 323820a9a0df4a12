#pragma once
// Helpers for the end-to-end tests: run the built tumble binary (or any program) with an argument
// vector — fork + exec, no shell, so no quoting problems — in a given working directory, capturing
// stdout, stderr and the exit code; a fresh temporary folder per test; small file helpers.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tumble_e2e {

namespace fs = std::filesystem;

/// Path of the tumble binary under test (set by tests/CMakeLists.txt).
inline const fs::path& tumble_binary() {
  static const fs::path path{TUMBLE_BINARY};
  return path;
}

/// The repository root (for assets/scenes and the like).
inline const fs::path& source_dir() {
  static const fs::path path{TUMBLE_SOURCE_DIR};
  return path;
}

struct RunResult {
  int exit_code = -1;      ///< the process's exit status; -1 when it did not exit normally
  int signal = 0;          ///< the signal that ended it, 0 when it exited
  bool timed_out = false;  ///< killed after the time limit
  std::string out;         ///< everything written to stdout
  std::string err;         ///< everything written to stderr
};

/// For assertion messages: the exit code and both streams.
inline std::string describe(const RunResult& r) {
  return "exit code " + std::to_string(r.exit_code) +
         (r.signal ? ", signal " + std::to_string(r.signal) : "") +
         (r.timed_out ? ", timed out" : "") + "\n--- stdout:\n" + r.out + "--- stderr:\n" + r.err;
}

struct RunOptions {
  std::chrono::milliseconds timeout = std::chrono::seconds(60);
  /// When `signal` is non-zero, it is sent to the program this long after the start (to test
  /// what an interrupted run leaves behind).
  std::chrono::milliseconds signal_after{0};
  int signal = 0;
};

/// Runs `program` (looked up in PATH when it has no '/') with `args` in the folder `cwd`,
/// stdin from /dev/null, and waits for it (at most `options.timeout`; then it is killed).
inline RunResult run_program(const std::string& program, const std::vector<std::string>& args,
                             const fs::path& cwd, const RunOptions& options = {}) {
  int out_pipe[2], err_pipe[2];
  if (pipe(out_pipe) != 0) throw std::runtime_error("pipe failed");
  if (pipe(err_pipe) != 0) {
    close(out_pipe[0]);
    close(out_pipe[1]);
    throw std::runtime_error("pipe failed");
  }
  // Built before fork: the child only calls async-signal-safe functions.
  std::vector<std::string> argv_storage;
  argv_storage.reserve(args.size() + 1);
  argv_storage.push_back(program);
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string dir = cwd.string();

  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int null_in = open("/dev/null", O_RDONLY);
    if (null_in < 0 || dup2(null_in, STDIN_FILENO) < 0) _exit(126);
    if (dup2(out_pipe[1], STDOUT_FILENO) < 0 || dup2(err_pipe[1], STDERR_FILENO) < 0) _exit(126);
    close(out_pipe[0]);
    close(out_pipe[1]);
    close(err_pipe[0]);
    close(err_pipe[1]);
    if (chdir(dir.c_str()) != 0) _exit(126);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  close(out_pipe[1]);
  close(err_pipe[1]);

  RunResult result;
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  std::string* sinks[2] = {&result.out, &result.err};
  int open_fds = 2;
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + options.timeout;
  bool signal_sent = options.signal == 0;
  while (open_fds > 0) {
    const auto now = std::chrono::steady_clock::now();
    if (!signal_sent && now >= start + options.signal_after) {
      kill(pid, options.signal);
      signal_sent = true;
    }
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now);
    if (!signal_sent)
      left = std::min(left, std::chrono::duration_cast<std::chrono::milliseconds>(
                                start + options.signal_after - now) +
                                std::chrono::milliseconds(1));
    if (left.count() <= 0) {
      kill(pid, SIGKILL);
      result.timed_out = true;
      break;
    }
    const int ready = poll(fds, 2, static_cast<int>(left.count()));
    if (ready < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      char buffer[65536];
      const ssize_t n = read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        sinks[i]->append(buffer, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        close(fds[i].fd);
        fds[i].fd = -1;
        --open_fds;
      }
    }
  }
  for (const pollfd& p : fds)
    if (p.fd >= 0) close(p.fd);

  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

/// Runs the tumble binary with `args` in the folder `cwd`.
inline RunResult run_tumble(const std::vector<std::string>& args, const fs::path& cwd,
                            const RunOptions& options = {}) {
  return run_program(tumble_binary().string(), args, cwd, options);
}

/// A fresh, empty folder for the running test: <tmp>/tumble-e2e-<uid>/<Suite>.<Test>/, emptied
/// when made. It is removed again at the end of a test that passed, and kept for a look after
/// one that failed.
class TestDir {
 public:
  TestDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "none";
    for (char& c : name)
      if (c == '/') c = '_';
    path_ = fs::temp_directory_path() / ("tumble-e2e-" + std::to_string(getuid())) / name;
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TestDir() {
    if (::testing::Test::HasFailure()) return;
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TestDir(const TestDir&) = delete;
  TestDir& operator=(const TestDir&) = delete;

  const fs::path& path() const { return path_; }
  fs::path operator/(const fs::path& p) const { return path_ / p; }

 private:
  fs::path path_;
};

/// Writes `text` to `path` (creating its folder), replacing whatever was there.
inline fs::path write_file(const fs::path& path, std::string_view text) {
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
  return path;
}

/// Writes a scene file `name` into `dir` and returns its path.
inline fs::path write_scene(const fs::path& dir, const std::string& name, std::string_view text) {
  return write_file(dir / name, text);
}

/// The whole content of a file ("" when it cannot be read; check existence separately).
inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// `text` with the first occurrence of `from` replaced by `to`; throws when `from` is absent so
/// a test cannot silently run on the unmodified text.
inline std::string replace(std::string text, std::string_view from, std::string_view to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos)
    throw std::logic_error("replace: \"" + std::string(from) + "\" not found");
  text.replace(at, from.size(), to);
  return text;
}

/// Every regular file under `root` whose file name is `name`, or that is a leftover temporary
/// (`.*.partial`) when `name` is empty.
inline std::vector<fs::path> find_files_named(const fs::path& root, std::string_view name) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    const std::string file = it->path().filename().string();
    const bool partial = file.size() > 8 && file.front() == '.' && file.ends_with(".partial");
    if (name.empty() ? partial : file == name) found.push_back(it->path());
  }
  return found;
}

/// The SHA-256 of a file as the system's `sha256sum` computes it (64 lower-case hex digits).
inline std::string system_sha256(const fs::path& file) {
  const RunResult r = run_program("sha256sum", {"-b", fs::absolute(file).string()}, "/");
  if (r.exit_code != 0 || r.out.size() < 64) return "sha256sum failed: " + describe(r);
  return r.out.substr(0, 64);
}

/// The file names in a folder, sorted (empty when it cannot be read).
inline std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// Every example scene in assets/scenes, sorted by name.
inline std::vector<fs::path> example_scenes() {
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(source_dir() / "assets/scenes"))
    if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

/// A small valid scene: a unit box dropped from 3 m onto a floor for 0.5 s. Line by line:
///  1 [simulation]   2 duration   3 [floor]   4 [[body]]   5 name   6 shape   7 size   8 mass
///  9 position (bad-input tests point at these lines).
inline constexpr std::string_view kDropScene = R"([simulation]
duration = 0.5
[floor]
[[body]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 3.0, 0.0]
)";

}  // namespace tumble_e2e
