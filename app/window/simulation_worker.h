// The window's background work, so that it keeps drawing and navigating: a frame of the
// simulation (and the view of it that the window will draw: frame_view.h), and opening a file (a
// scene may need meshing first). Each runs on its own thread; the window collects the result
// between its frames without waiting for it, and tools act only between simulation frames,
// exactly as recorded.
#pragma once

#include <filesystem>
#include <functional>
#include <future>
#include <mutex>
#include <optional>
#include <string>

#include "app/window/frame_view.h"
#include "engine/scene/scene.h"
#include "engine/session/session_loader.h"

namespace galsculpt {

class FrameWorker {
 public:
  bool inFlight() const { return frame_.valid(); }
  bool ready() const;  // in flight and finished
  // One frame of `session`, then its view in `style`; `done` runs on the worker when both are
  // (the window wakes on it).
  void start(SculptSession& session, const SurfaceStyle& style, std::function<void()> done);
  FrameView wait();  // the frame's view (in flight only)

 private:
  std::future<FrameView> frame_;
};

class OpenWorker {
 public:
  bool busy() const { return opening_.valid(); }
  bool ready() const;  // busy and finished
  // Does nothing while busy.
  void start(const std::filesystem::path& file, const SolverOverrides& solver);
  // The opened session; throws what opening threw. Busy no more either way.
  OpenedSession take();
  void wait() const;
  const std::filesystem::path& file() const { return file_; }
  std::string progress() const;

 private:
  std::future<OpenedSession> opening_;
  std::filesystem::path file_;
  mutable std::mutex progressMutex_;
  std::string progress_;
};

}  // namespace galsculpt
