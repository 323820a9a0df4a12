#include "tumble/output_target.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <system_error>

#include "cannot_write.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

std::string errno_text(int code) {
  return std::generic_category().message(code);
}

// The folder a path is in, "." for a bare name.
fs::path folder_of(const fs::path& p) {
  return p.has_parent_path() ? p.parent_path() : fs::path(".");
}

// Follows symbolic links to what they finally name (which need not exist yet). Linux gives up
// after 40 links (ELOOP); so does this.
fs::path follow_links(const fs::path& path) {
  constexpr int kMaxLinks = 40;
  fs::path p = path;
  for (int i = 0; i < kMaxLinks; ++i) {
    struct stat st {};
    if (lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    std::error_code ec;
    const fs::path to = fs::read_symlink(p, ec);
    if (ec) cannot_write(path, ec.message());
    p = to.is_absolute() ? to : folder_of(p) / to;
  }
  cannot_write(path, errno_text(ELOOP));
}

// Six characters no other process or thread picks at the same time, with overwhelming
// likelihood; O_EXCL (mkdir) turns the rare collision into a retry rather than a clobber.
std::string random_letters() {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  static std::atomic<unsigned> counter{0};
  thread_local std::mt19937_64 generator = [] {
    std::random_device device;
    timespec now{};
    clock_gettime(CLOCK_REALTIME, &now);
    std::seed_seq seed{device(), device(), static_cast<unsigned>(getpid()),
                       static_cast<unsigned>(now.tv_nsec), counter.fetch_add(1)};
    return std::mt19937_64(seed);
  }();
  std::string s(6, 'x');
  for (char& c : s) c = kAlphabet[generator() % (sizeof kAlphabet - 1)];
  return s;
}

template <class Make>
fs::path make_unique(const fs::path& folder, std::string_view stem, Make make) {
  constexpr int kAttempts = 100;
  int last_error = EEXIST;
  for (int i = 0; i < kAttempts && last_error == EEXIST; ++i) {
    std::string name = ".";
    name.append(stem);
    name += '.';
    name += random_letters();
    name += ".partial";
    const fs::path p = folder / name;
    if (make(p)) return p;
    last_error = errno;
  }
  cannot_write(folder / stem, errno_text(last_error));
}

// Writes every byte of `from` into the open descriptor `fd`; false with errno set on failure.
bool copy_into(const fs::path& from, int fd) {
  const int in = open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) return false;
  char buffer[1 << 16];
  bool ok = true;
  for (;;) {
    const ssize_t n = read(in, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ok = n == 0;
      break;
    }
    for (ssize_t done = 0; ok && done < n;) {
      const ssize_t w = write(fd, buffer + done, static_cast<std::size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w < 0) ok = false;
      if (w > 0) done += w;
    }
    if (!ok) break;
  }
  const int saved = errno;
  close(in);
  errno = saved;
  return ok;
}

// Writes `finished` through into a device or FIFO. A reader that goes away (`| head`) would
// raise SIGPIPE and kill the process before it could clean up: the signal is blocked on this
// thread for the copy, so the write fails with EPIPE instead, and a pending one is consumed.
void write_through(const fs::path& finished, const OutputTarget& target) {
  sigset_t pipe_only, previous;
  sigemptyset(&pipe_only);
  sigaddset(&pipe_only, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_only, &previous);
  // O_WRONLY without O_CREAT or O_TRUNC: the node is there and is never replaced.
  const int fd = open(target.resolved.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  bool ok = fd >= 0 && copy_into(finished, fd);
  int error = errno;
  if (fd >= 0 && close(fd) != 0 && ok) {
    ok = false;
    error = errno;
  }
  if (!ok && error == EPIPE) {
    const timespec no_wait{};
    sigtimedwait(&pipe_only, nullptr, &no_wait);
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  if (!ok) cannot_write(target.path, errno_text(error));
  std::error_code ignored;
  fs::remove(finished, ignored);
}

}  // namespace

OutputTarget output_target(const fs::path& path) {
  OutputTarget t;
  t.path = path;
  struct stat st {};
  // stat() follows every link, /proc's too: /dev/stdout → /proc/self/fd/1 → "pipe:[1234]" is
  // a FIFO to stat() but no path to read_symlink(). A device or FIFO is opened by the path as
  // given (open() follows the same links), so it needs no resolving.
  if (stat(path.c_str(), &st) == 0) {
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
      t.resolved = path;
      t.kind = OutputTarget::Kind::WriteThrough;
      return t;
    }
    if (S_ISDIR(st.st_mode)) cannot_write(path, "it is a folder");
    if (!S_ISREG(st.st_mode)) cannot_write(path, "it is neither a file, a character device nor a FIFO");
  } else if (errno != ENOENT && errno != ENOTDIR) {
    cannot_write(path, errno_text(errno));
  }
  // A regular file, or nothing yet (a dangling link: what it names): replaced by a rename over
  // what the links name, so the links stay, and beside it, so the rename stays on one file system.
  t.resolved = follow_links(path);
  t.kind = OutputTarget::Kind::Replace;
  const fs::path folder = folder_of(t.resolved);
  if (stat(folder.c_str(), &st) != 0)
    cannot_write(path, errno == ENOENT ? "the folder \"" + folder.string() +
                                     "\" does not exist (tumble creates only --out folders)"
                               : errno_text(errno));
  if (!S_ISDIR(st.st_mode)) cannot_write(path, "\"" + folder.string() + "\" is not a folder");
  return t;
}

void place_output(const fs::path& finished, const OutputTarget& target) {
  if (target.kind == OutputTarget::Kind::WriteThrough) {
    write_through(finished, target);
    return;
  }
  if (std::rename(finished.c_str(), target.resolved.c_str()) == 0) return;
  if (errno != EXDEV) cannot_write(target.path, errno_text(errno));
  // A link into another file system: a copy beside what it names, then the same atomic rename.
  const fs::path copy =
      make_unique_temporary_file(folder_of(target.resolved), target.resolved.filename().string());
  std::error_code ec;
  fs::copy_file(finished, copy, fs::copy_options::overwrite_existing, ec);
  if (!ec && std::rename(copy.c_str(), target.resolved.c_str()) != 0)
    ec = std::error_code(errno, std::generic_category());
  if (ec) {
    std::error_code ignored;
    fs::remove(copy, ignored);
    cannot_write(target.path, ec.message());
  }
  fs::remove(finished, ec);
}

fs::path make_unique_temporary_file(const fs::path& folder, std::string_view stem) {
  return make_unique(folder, stem, [](const fs::path& p) {
    // 0666 less the umask, as any new file gets (mkstemp's 0600 would make outputs private).
    const int fd = open(p.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) return false;
    close(fd);
    return true;
  });
}

fs::path make_unique_temporary_folder(const fs::path& folder, std::string_view stem) {
  return make_unique(folder, stem, [](const fs::path& p) { return mkdir(p.c_str(), 0777) == 0; });
}

}  // namespace tumble
