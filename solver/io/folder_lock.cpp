#include "solver/io/folder_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

// The pid the holder wrote into the lock file, or "unknown".
std::string holderOf(const fs::path& file) {
  const int fd = open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return "unknown";
  char text[32] = {};
  const ssize_t n = read(fd, text, sizeof text - 1);
  close(fd);
  std::string pid(text, n > 0 ? static_cast<size_t>(n) : 0);
  return pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos ? "unknown" : pid;
}

}  // namespace

FolderLock::FolderLock(const fs::path& dir) : file_(dir / kFileName) {
  // A file removed by a holder that just finished may be the one opened here: then the lock
  // taken is on a file no longer in the folder, so take it again on the current one.
  for (int attempt = 0; attempt < 100; ++attempt) {
    fd_ = open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0)
      throw OutputError("cannot write into " + dir.string() + ": cannot create " +
                        file_.filename().string() + ": " + std::strerror(errno));
    if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      close(fd_);
      fd_ = -1;
      if (error == EWOULDBLOCK)
        throw OutputError("cannot write into " + dir.string() + ": another galsculpt (pid " +
                          holderOf(file_) +
                          ") is writing there; wait for it or choose another --out");
      throw OutputError("cannot write into " + dir.string() + ": cannot lock " +
                        file_.filename().string() + ": " + std::strerror(error));
    }
    struct stat held {
    }, named{};
    if (fstat(fd_, &held) == 0 && stat(file_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      const std::string pid = std::to_string(getpid());
      if (ftruncate(fd_, 0) != 0 || pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
        // The pid is only for the other writer's message; the lock holds without it.
      }
      return;
    }
    close(fd_);
    fd_ = -1;
  }
  throw OutputError("cannot write into " + dir.string() + ": its lock keeps changing");
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  // Removed while still held, so the next writer never takes a lock on a file that is gone.
  unlink(file_.c_str());
  close(fd_);
}

}  // namespace galsculpt
