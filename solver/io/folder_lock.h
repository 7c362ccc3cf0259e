// One writer per output folder: `run` and `play` hold an advisory lock (flock) on a hidden file
// in their output folder while they write there, so a second command given the same folder is
// refused, naming the first one's pid, instead of both exiting 0 over a folder that mixes their
// frames. The lock ends with its holder, however it ends (a kill -9 included).
#pragma once

#include <filesystem>

namespace galsculpt {

class FolderLock {
 public:
  // Throws OutputError when another process holds `dir`'s lock or the lock cannot be made.
  explicit FolderLock(const std::filesystem::path& dir);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  static constexpr const char* kFileName = ".galsculpt-writer";

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

}  // namespace galsculpt
