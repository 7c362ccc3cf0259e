#include "app/window/simulation_worker.h"

#include <chrono>

#include "solver/io/stop_request.h"

namespace galsculpt {

namespace {
template <typename T>
bool finished(const std::future<T>& f) {
  return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}
}  // namespace

bool FrameWorker::ready() const {
  return finished(frame_);
}

void FrameWorker::start(SculptSession& session, const SurfaceStyle& style,
                        std::function<void()> done) {
  SculptSession* s = &session;
  frame_ = std::async(std::launch::async, [s, style, done = std::move(done)] {
    FrameMetrics metrics;
    try {
      metrics = s->step();
    } catch (const Interrupted&) {
      // Ctrl-C or SIGTERM cut the frame short (the state is the last whole frame's): the
      // window closes as it sees the stop, its session kept for recovery.
      metrics.frame = s->simulation().frame();
    }
    FrameView view = makeFrameView(*s, style, metrics);
    view.readyAt = std::chrono::steady_clock::now();
    if (done) done();
    return view;
  });
}

FrameView FrameWorker::wait() {
  return frame_.get();
}

bool OpenWorker::ready() const {
  return finished(opening_);
}

void OpenWorker::start(const std::filesystem::path& file, const SolverOverrides& solver) {
  if (busy()) return;
  file_ = file;
  {
    std::lock_guard<std::mutex> lock(progressMutex_);
    progress_ = "opening " + file.string();
  }
  opening_ = std::async(std::launch::async, [this, file, solver] {
    return openSession(
        file,
        [this](const std::string& line) {
          std::lock_guard<std::mutex> lock(progressMutex_);
          progress_ = line;
        },
        20000, solver);
  });
}

OpenedSession OpenWorker::take() {
  std::future<OpenedSession> f = std::move(opening_);
  return f.get();
}

void OpenWorker::wait() const {
  if (busy()) opening_.wait();
}

std::string OpenWorker::progress() const {
  std::lock_guard<std::mutex> lock(progressMutex_);
  return progress_;
}

}  // namespace galsculpt
