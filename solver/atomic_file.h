// Atomic file output: write to a temporary file beside the target, then rename over it.
//
// A crash, a full disk or a failed stream leaves the previous file untouched, and readers never
// see a half-written file. Errors are thrown as OutputError naming the path and the reason.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace galsculpt {

// Calls write(stream) on a temporary file in the target's directory and renames it to `path`.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);

// Reads a whole file into memory; throws InputError when it cannot be opened.
std::string readWholeFile(const std::filesystem::path& path);

}  // namespace galsculpt
