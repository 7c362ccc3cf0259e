#include "solver/io/appending_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "solver/io/input_error.h"

namespace galsculpt {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, int error) {
  throw OutputError("cannot write " + path.string() + ": " + std::strerror(error));
}

}  // namespace

AppendingFile::AppendingFile(const std::filesystem::path& path) : path_(path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw OutputError("cannot write " + path.string() + ": a folder is in its place");
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail(path, errno);
}

AppendingFile::~AppendingFile() {
  if (fd_ >= 0) ::close(fd_);
}

void AppendingFile::append(std::string_view record) {
  if (fd_ < 0) throw OutputError("cannot write " + path_.string() + ": the file is closed");
  std::size_t done = 0;
  while (done < record.size()) {
    const ssize_t n = ::write(fd_, record.data() + done, record.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : ENOSPC;
      // The file keeps whole records only.
      if (ftruncate(fd_, static_cast<off_t>(size_)) == 0) lseek(fd_, 0, SEEK_END);
      fail(path_, error);
    }
    done += static_cast<std::size_t>(n);
  }
  size_ += record.size();
}

void AppendingFile::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(path_, errno);
}

}  // namespace galsculpt
