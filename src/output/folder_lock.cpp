#include "tumble/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <system_error>

#include "tumble/error.hpp"

namespace tumble {
namespace {

[[noreturn]] void cannot_lock(const std::filesystem::path& dir, const std::string& why) {
  throw Error(ErrorKind::Environment,
              "cannot lock the output folder \"" + dir.string() + "\": " + why);
}

// The holder's process id as it wrote it ("" when it has not yet, or the file is not ours).
std::string holder_pid(int fd) {
  char text[24] = {};
  const ssize_t n = pread(fd, text, sizeof text - 1, 0);
  std::string pid;
  for (ssize_t i = 0; i < n && text[i] >= '0' && text[i] <= '9'; ++i) pid += text[i];
  return pid;
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& dir) : path_(dir / kFileName) {
  // The holder removes the file when it is done; a run that opened it just before may then hold
  // a lock on a file no longer in the folder. It notices (the folder's file is another, or none)
  // and tries again on the new one, so at most one lock on the file in the folder is held.
  constexpr int kAttempts = 100;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    const int fd = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd < 0) cannot_lock(dir, std::generic_category().message(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string pid = error == EWOULDBLOCK ? holder_pid(fd) : "";
      close(fd);
      if (error == EINTR) continue;
      if (error != EWOULDBLOCK) cannot_lock(dir, std::generic_category().message(error));
      throw Error(ErrorKind::Environment,
                  "the output folder \"" + dir.string() + "\" is in use: another tumble run" +
                      (pid.empty() ? "" : " (process " + pid + ")") +
                      " is writing it; wait for it to end or choose another --out");
    }
    struct stat held {
    }, named{};
    if (fstat(fd, &held) == 0 && stat(path_.c_str(), &named) == 0 && held.st_dev == named.st_dev &&
        held.st_ino == named.st_ino) {
      fd_ = fd;
      // For the message a second run prints; the lock itself is the flock, not this text.
      const std::string pid = std::to_string(getpid()) + "\n";
      if (ftruncate(fd_, 0) != 0 || pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
        // Only the message loses the process id; the lock is held.
      }
      return;
    }
    close(fd);
  }
  cannot_lock(dir, "the lock file keeps changing");
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  // Removed while still held, so no other run can hold a lock on this file in the folder.
  unlink(path_.c_str());
  close(fd_);
}

}  // namespace tumble
