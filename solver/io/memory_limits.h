// How much memory this process may still take: what a command checks before it asks for a
// large amount (a tet mesh of many tets) and names when an allocation fails.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace galsculpt {

// The least of the kernel's estimate of memory available without swapping (/proc/meminfo
// MemAvailable), the cgroup's limit less its use (cgroup v2 memory.max - memory.current; a
// container's or a systemd unit's) and the address-space limit (ulimit -v) less what the process
// has mapped; none when none of them can be read.
std::optional<std::uint64_t> availableMemoryBytes();

// "20.4 GB", "512 MB", "3.1 kB": decimal units, three digits at most.
std::string bytesText(double bytes);

// "; about 7.5 GB is available" (empty when the available memory is not known): for messages.
std::string availableMemoryText();

// Work refused for want of memory: Python's MemoryError, the command line's failure exit.
struct OutOfMemory : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws OutOfMemory ("out of memory before starting: WHAT needs about 3.0 GB; about 1.9 GB is
// available: HINT") when `bytes` is more than is available; nothing when that is not known.
void requireMemory(double bytes, const std::string& what, const std::string& hint);

}  // namespace galsculpt
