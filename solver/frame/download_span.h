// One array of a batched device-to-host copy (Exec::downloadAll): the copies are queued behind
// the launches and delivered together, behind one host wait.
#pragma once

#include <cstddef>

namespace galsculpt {

struct DownloadSpan {
  const void* device;
  void* host;
  std::size_t bytes;
};

}  // namespace galsculpt
