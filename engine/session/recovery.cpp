#include "engine/session/recovery.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>

#include "engine/session/project_file.h"
#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPrefix = "recovery-";
constexpr const char* kSuffix = ".gsproj";

// The pid in recovery-<pid>.gsproj, or -1.
long pidOf(const fs::path& file) {
  const std::string name = file.filename().string();
  const std::string prefix = kPrefix, suffix = kSuffix;
  if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
      name.substr(name.size() - suffix.size()) != suffix)
    return -1;
  const std::string digits =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::strtol(digits.c_str(), nullptr, 10);
}

bool running(long pid) {
  return kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

}  // namespace

fs::path RecoveryStore::defaultFolder() {
  if (const char* d = std::getenv("GALSCULPT_RECOVERY_DIR"); d && *d) return d;
  if (const char* d = std::getenv("XDG_STATE_HOME"); d && *d) return fs::path(d) / "galsculpt";
  if (const char* h = std::getenv("HOME"); h && *h)
    return fs::path(h) / ".local" / "state" / "galsculpt";
  return fs::temp_directory_path() / "galsculpt";
}

RecoveryStore::RecoveryStore(fs::path folder)
    : folder_(std::move(folder)),
      own_(folder_ / (kPrefix + std::to_string(static_cast<long>(getpid())) + kSuffix)) {}

std::vector<fs::path> RecoveryStore::orphans() const {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder_, ec)) {
    // Only regular files are ours: a pipe or a device put there would block the offer's read.
    if (!isRegularFile(e.path())) continue;
    const long pid = pidOf(e.path());
    if (pid > 0 && e.path() != own_ && !running(pid)) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end(), [](const fs::path& a, const fs::path& b) {
    std::error_code e1, e2;
    return fs::last_write_time(a, e1) > fs::last_write_time(b, e2);
  });
  return out;
}

void RecoveryStore::save(const SculptSession& session,
                         const std::optional<CameraPose>& camera) const {
  std::error_code ec;
  fs::create_directories(folder_, ec);
  if (ec) throw OutputError("cannot create " + folder_.string() + ": " + ec.message());
  writeProject(own_, session, camera);
}

void RecoveryStore::remove(const fs::path& file) const {
  std::error_code ec;
  fs::remove(file, ec);
}

}  // namespace galsculpt
