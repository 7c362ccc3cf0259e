// What a run or play writes into its --out folder: which files are its kind, the earlier run's
// ones cleared before a new run writes, and the closing list of what this one wrote.
//
// A run owns its output: files that an earlier `run` or `play` wrote under the names these
// commands use (metrics.csv, final.*, frame_NNNNN.*) and that this run would not overwrite could
// be mistaken for this run's, so they are removed before the first frame, and said. Anything
// else in the folder is left as it is.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace galsculpt {

// Whether `name` is a file name `run` or `play` writes (metrics.csv, final.EXT, frame_NNNNN.EXT
// with an extension they write).
bool isRunOutputName(const std::string& name);

// The run outputs in `dir` (plain files, not its subfolders), sorted. Throws OutputError when
// the folder cannot be listed.
std::vector<std::string> runOutputsIn(const std::filesystem::path& dir);

// Removes the run outputs in `dir`; returns their names, sorted. Throws OutputError naming a
// file that cannot be removed.
std::vector<std::string> clearRunOutputs(const std::filesystem::path& dir);

// The files written, one line: plain names, with frame_NNNNN.EXT files counted per extension
// ("120 frame_*.obj (frame_00001.obj .. frame_00120.obj)").
std::string describeWritten(std::vector<std::string> names);

}  // namespace galsculpt
