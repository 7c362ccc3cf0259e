#include "solver/io/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <random>
#include <sstream>

#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

// Temporaries of `path` left behind by processes that are gone (a kill -9 mid-write) are
// removed; a live writer's are left alone.
void removeStaleTemporaries(const fs::path& dir, const std::string& name) {
  // ".NAME.tmpPID": a member being written; ".NAME.oldPID": the one it replaces, moved aside
  // while a set is committed.
  const std::string tmpPrefix = "." + name + ".tmp", oldPrefix = "." + name + ".old";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    const std::string& prefix =
        entry.compare(0, oldPrefix.size(), oldPrefix) == 0 ? oldPrefix : tmpPrefix;
    if (entry.size() <= prefix.size() || entry.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string pid = entry.substr(prefix.size());
    if (pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    const pid_t owner = static_cast<pid_t>(std::stol(pid));
    if (owner == getpid() || (kill(owner, 0) != 0 && errno == ESRCH)) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

// Writes `path`'s content to its temporary and returns the temporary's path.
fs::path writeTemporary(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw OutputError("cannot write " + path.string() + ": directory " + dir.string() +
                      " does not exist");
  }
  removeStaleTemporaries(dir, path.filename().string());
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on chained operator+ here.
  std::string tmpName = ".";
  tmpName.append(path.filename().string()).append(".tmp").append(std::to_string(getpid()));
  const fs::path tmp = dir / tmpName;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw OutputError("cannot write " + path.string() + ": " + std::strerror(errno));
    }
    try {
      write(out);
    } catch (...) {
      out.close();
      fs::remove(tmp, ec);
      throw;
    }
    out.flush();
    if (out) out.close();  // the last of the data may only fail here
    if (!out) {
      const std::string reason = std::strerror(errno != 0 ? errno : EIO);
      out.close();
      fs::remove(tmp, ec);
      throw OutputError("cannot write " + path.string() + ": " + reason);
    }
  }
  return tmp;
}

// fsync of a file or a folder (opened read-only, which Linux allows); errno on failure, else 0.
int syncPath(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return errno;
  const int error = fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  return error;
}

void commitTemporary(const fs::path& tmp, const fs::path& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string reason = ec.message();  // before the clean-up overwrites ec
    fs::remove(tmp, ec);
    throw OutputError("cannot write " + path.string() + ": " + reason);
  }
}

FileSet::RenameFn renameForTesting = nullptr;

void renameFile(const fs::path& from, const fs::path& to, std::error_code& ec) {
  if (renameForTesting)
    renameForTesting(from, to, ec);
  else
    fs::rename(from, to, ec);
}

constexpr char kStampPrefix[] = "# galsculpt set ";

}  // namespace

void writeFileAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  commitTemporary(writeTemporary(path, write), path);
}

void writeFileDurably(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  const fs::path tmp = writeTemporary(path, write);
  if (const int error = syncPath(tmp)) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw OutputError("cannot write " + path.string() + ": " + std::strerror(error));
  }
  commitTemporary(tmp, path);
  // The rename itself is on disk once the folder is: a crash later cannot bring the old back.
  if (const int error = syncPath(tmp.parent_path()))
    throw OutputError("cannot write " + path.string() + ": " + std::strerror(error));
}

FileSet::FileSet() {
  std::random_device device;
  std::ostringstream s;
  s << std::hex << std::setfill('0') << std::setw(8) << device() << std::setw(8) << device();
  stamp_ = s.str();
}

FileSet::~FileSet() {
  for (const auto& [tmp, target] : written_) {
    std::error_code ec;
    fs::remove(tmp, ec);
  }
}

std::string FileSet::stampLine() const {
  return std::string(kStampPrefix) + stamp_ + "\n";
}

void FileSet::add(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  written_.emplace_back(writeTemporary(path, write), path);
}

void FileSet::remove(const fs::path& path) {
  removed_.push_back(path);
}

void FileSet::setRenameForTesting(RenameFn rename) {
  renameForTesting = rename;
}

void FileSet::commit() {
  std::error_code ec;
  for (const auto& [tmp, target] : written_) {
    if (fs::is_directory(fs::symlink_status(target, ec)))
      throw OutputError("cannot write " + target.string() + ": a folder is in its place");
  }
  // Members already in place move aside (".NAME.oldPID"), then the new ones take their places;
  // a failure puts every moved member back.
  std::vector<std::pair<fs::path, fs::path>> aside;  // where it went, where it was
  std::vector<fs::path> placed;
  auto putBack = [&] {
    std::error_code ignored;
    for (const fs::path& p : placed) fs::remove(p, ignored);
    for (auto it = aside.rbegin(); it != aside.rend(); ++it)
      renameFile(it->first, it->second, ignored);
    for (const auto& [tmp, target] : written_) fs::remove(tmp, ignored);
    written_.clear();
  };
  for (const auto& [tmp, target] : written_) {
    if (fs::exists(fs::symlink_status(target, ec))) {
      std::string name = ".";
      name.append(target.filename().string()).append(".old").append(std::to_string(getpid()));
      const fs::path old = target.parent_path() / name;
      renameFile(target, old, ec);
      if (ec) {
        const std::string message = "cannot write " + target.string() +
                                    ": cannot move the old one aside: " + ec.message() +
                                    "; the old set is unchanged";
        putBack();  // clears written_, which `target` refers into
        throw OutputError(message);
      }
      aside.emplace_back(old, target);
    }
    renameFile(tmp, target, ec);
    if (ec) {
      const std::string message =
          "cannot write " + target.string() + ": " + ec.message() + "; the old set is unchanged";
      putBack();  // clears written_, which `target` refers into
      throw OutputError(message);
    }
    placed.push_back(target);
  }
  for (const auto& [old, target] : aside) fs::remove(old, ec);
  written_.clear();
  for (const fs::path& p : removed_) {
    std::error_code ec;
    fs::remove(p, ec);
    if (ec) throw OutputError("cannot remove the stale " + p.string() + ": " + ec.message());
  }
}

std::string findSetStamp(const std::string& text) {
  const size_t at = text.rfind(kStampPrefix);
  if (at == std::string::npos) return {};
  const size_t begin = at + sizeof(kStampPrefix) - 1;
  size_t end = begin;
  while (end < text.size() && std::isxdigit(static_cast<unsigned char>(text[end]))) ++end;
  return text.substr(begin, end - begin);
}

void requireRegularFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec && ec == std::errc::too_many_symbolic_link_levels)
    throw InputError(path.string(), 0, "is a loop of symbolic links");
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw InputError(path.string(), 0, "cannot be read: " + ec.message());
  if (!fs::exists(status)) throw InputError(path.string(), 0, "file not found");
  if (fs::is_regular_file(status)) return;
  const char* what = fs::is_directory(status)        ? "is a folder"
                     : fs::is_fifo(status)           ? "is a named pipe (FIFO)"
                     : fs::is_socket(status)         ? "is a socket"
                     : fs::is_block_file(status)     ? "is a block device"
                     : fs::is_character_file(status) ? "is a character device"
                                                     : "is a special file";
  throw InputError(path.string(), 0, std::string(what) + ", not a regular file");
}

void requirePathExists(const fs::path& path) {
  std::error_code ec;
  const bool exists = fs::exists(path, ec);
  if (ec) requireRegularFile(path);  // says why
  if (!exists) throw InputError(path.string() + ": no such file");
}

bool isRegularFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(fs::status(path, ec)) && !ec;
}

std::string readWholeFile(const fs::path& path) {
  // Only regular files, and their size known before anything is allocated: a device such as
  // /dev/zero or a pipe would otherwise be read until memory runs out.
  requireRegularFile(path);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path.string(), 0, "cannot read its size: " + ec.message());
  if (size > kMaxInputFileBytes)
    throw InputError(path.string(), 0,
                     "is " + std::to_string(size) + " bytes; input files are limited to " +
                         std::to_string(kMaxInputFileBytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, std::string("cannot open: ") + std::strerror(errno));
  std::string data(static_cast<size_t>(size), '\0');
  in.read(data.data(), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size)
    throw InputError(path.string(), 0,
                     "changed while it was read (expected " + std::to_string(size) + " bytes)");
  return data;
}

}  // namespace galsculpt
