// A file written a record at a time under its final name (the metrics CSV of `run` and `play`):
// each record reaches the file as it is appended, so a process ended by a signal, a kill -9 or
// a crash leaves every record written so far, each one whole. A failed write (a full disk, a
// file size limit) cuts the partial record off again and throws OutputError naming the path.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>

namespace galsculpt {

class AppendingFile {
 public:
  // Creates the file, or empties the one there; throws OutputError when it cannot.
  explicit AppendingFile(const std::filesystem::path& path);
  ~AppendingFile();
  AppendingFile(const AppendingFile&) = delete;
  AppendingFile& operator=(const AppendingFile&) = delete;

  void append(std::string_view record);
  // Closes the file; throws OutputError when the system reports that the data did not land.
  void close();
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;  // bytes of whole records
};

}  // namespace galsculpt
