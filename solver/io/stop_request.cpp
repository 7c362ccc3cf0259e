#include "solver/io/stop_request.h"

#include <signal.h>

#include <atomic>

namespace galsculpt {

namespace {

std::atomic<int> requested{0};
std::atomic<StopPoller> poller{nullptr};
static_assert(std::atomic<int>::is_always_lock_free, "read and written inside a signal handler");

void onStopSignal(int signal) {
  if (requested.exchange(signal) != 0) {  // the second one: no more waiting for a clean end
    ::signal(signal, SIG_DFL);
    raise(signal);
  }
}

}  // namespace

Interrupted::Interrupted(int signal)
    : std::runtime_error("stopped by " + signalName(signal)), signal_(signal) {}

void installStopHandlers() {
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int stopSignal() {
  int signal = requested.load(std::memory_order_relaxed);
  if (signal == 0) {
    if (const StopPoller poll = poller.load(std::memory_order_relaxed)) {
      signal = poll();
      if (signal != 0) requested.store(signal);
    }
  }
  return signal;
}

void setStopPoller(StopPoller poll) {
  poller.store(poll);
}

void clearStopRequest() {
  requested.store(0);
}

void throwIfStopRequested() {
  if (const int signal = stopSignal()) throw Interrupted(signal);
}

std::string signalName(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal);
}

void requestStopForTesting(int signal) {
  requested.store(signal);
}

}  // namespace galsculpt
