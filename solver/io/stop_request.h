// A stop asked for by SIGINT or SIGTERM, ended cleanly: the handler only records the signal;
// the long loops (frames, TetGen runs, replays, bench windows) poll it and throw Interrupted,
// so that every destructor on the way out runs (temporaries and TetGen folders removed, locks
// released) and what was written stays whole. main then ends the process with the same signal,
// as a shell expects. A second signal while the first is handled ends the process at once.
#pragma once

#include <stdexcept>
#include <string>

namespace galsculpt {

class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  int signal() const { return signal_; }

 private:
  int signal_;
};

// SIGINT and SIGTERM record a stop (system calls restart; nothing else happens in the handler).
void installStopHandlers();
// The signal of the stop asked for, or 0.
int stopSignal();
inline bool stopRequested() {
  return stopSignal() != 0;
}
// Throws Interrupted when a stop was asked for.
void throwIfStopRequested();
// "SIGINT", "SIGTERM" or "signal N".
std::string signalName(int signal);

// Tests: records a stop as the handler does (0 clears it).
void requestStopForTesting(int signal);

// An embedding's own signal handling (Python's): while set, stopSignal() asks `poll` when no
// stop is recorded, and records what it returns (a signal, or 0). Null: none. clearStopRequest()
// forgets a recorded stop once the embedding has handled it.
using StopPoller = int (*)();
void setStopPoller(StopPoller poll);
void clearStopRequest();

}  // namespace galsculpt
