// Atomic file output: write to a temporary file beside the target, then rename over it.
//
// A crash, a full disk or a failed stream leaves the previous file untouched, and readers never
// see a half-written file. Errors are thrown as OutputError naming the path and the reason.
#pragma once

#include <cstdint>

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace galsculpt {

// Calls write(stream) on a temporary file in the target's directory and renames it to `path`.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);
// The same, for files that promise to survive a crash of the machine (projects, autosaves):
// the data reaches the disk (fsync) before the rename, and the rename before it returns.
void writeFileDurably(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write);

// Files that belong together (a TetGen mesh, its .face and its .damage) committed as a whole:
// every member is written to a temporary beside its target first, and only once all of them
// are complete are they renamed into place, so an error or a kill while writing leaves the
// previous set untouched. Renames cannot be one atomic step, so each member also carries the
// set's stamp (`stampLine()`, a comment line its reader skips) and readers refuse a set whose
// members carry different stamps: a kill between two renames is detected, never read as one
// mesh. Members listed with `remove` (stale files of the set not written this time) are deleted
// on commit. Temporaries left by killed processes are cleaned by the next write beside them.
class FileSet {
 public:
  FileSet();  // with a fresh stamp
  FileSet(const FileSet&) = delete;
  FileSet& operator=(const FileSet&) = delete;
  ~FileSet();  // removes temporaries of an uncommitted set

  const std::string& stamp() const { return stamp_; }
  // "# galsculpt set <stamp>\n": the line every member writes.
  std::string stampLine() const;
  // Writes the member to its temporary now (throws OutputError, the set then unchanged).
  void add(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);
  void remove(const std::filesystem::path& path);
  // Renames every member into place and deletes the removed ones, as a whole: the members
  // already there are moved aside first, and when one cannot be renamed into place every one is
  // put back (the folder holds the old set, never a mix) and OutputError says why. A member
  // whose place is taken by a folder fails before anything moves.
  void commit();

  // Tests: the rename the commit uses, to make one fail (nullptr: std::filesystem::rename).
  using RenameFn = void (*)(const std::filesystem::path& from, const std::filesystem::path& to,
                            std::error_code& ec);
  static void setRenameForTesting(RenameFn rename);

 private:
  std::string stamp_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> written_;  // tmp, target
  std::vector<std::filesystem::path> removed_;
};

// The stamp of a set member's text (its last "# galsculpt set" line), empty when it has none
// (written by another program or by an older Galsculpt).
std::string findSetStamp(const std::string& text);

// Input files larger than this are refused before anything is read (4 GiB: far above any
// mesh, scene or project the app handles on a 24 GiB machine).
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{4} << 30;

// Throws InputError naming the path and the reason unless it is a regular file (after
// symbolic links): missing, a loop of symbolic links, a folder, a named pipe, a socket, a
// device. Checked before a file is opened for reading, so nothing waits on a pipe's writer.
void requireRegularFile(const std::filesystem::path& path);
// Throws InputError "PATH: no such file" when nothing is there, or why it cannot be told
// (requireRegularFile's reasons: a loop of symbolic links, no permission).
void requirePathExists(const std::filesystem::path& path);
// The same as a question: whether `path` is a regular file (after symbolic links).
bool isRegularFile(const std::filesystem::path& path);

// Reads a whole regular file into memory; throws InputError when it is missing, not a regular
// file (requireRegularFile), larger than kMaxInputFileBytes or cannot be read.
std::string readWholeFile(const std::filesystem::path& path);

}  // namespace galsculpt
