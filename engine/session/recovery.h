// Autosave and crash recovery. Each running app autosaves its session as a project into
// recovery-<pid>.gsproj in the recovery folder ($GALSCULPT_RECOVERY_DIR, else
// $XDG_STATE_HOME/galsculpt, else ~/.local/state/galsculpt) and removes it when it closes
// normally. A file whose process is gone was left by a crash: the next start offers it.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "engine/session/sculpt_session.h"

namespace galsculpt {

class RecoveryStore {
 public:
  explicit RecoveryStore(std::filesystem::path folder = defaultFolder());
  static std::filesystem::path defaultFolder();

  const std::filesystem::path& ownFile() const { return own_; }
  // Files left by processes that are no longer running, newest first.
  std::vector<std::filesystem::path> orphans() const;
  // Writes the session atomically (creating the folder); throws OutputError.
  void save(const SculptSession& session, const std::optional<CameraPose>& camera) const;
  // Removes this process's file (a normal exit) or a recovered / declined orphan.
  void remove(const std::filesystem::path& file) const;

 private:
  std::filesystem::path folder_, own_;
};

}  // namespace galsculpt
