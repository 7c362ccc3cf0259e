#include "app/cli/run_outputs.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

// Extensions the surfaces, pictures and tet meshes of a run are written with (a .gltf brings
// its .bin).
const std::set<std::string> kOutputExtensions = {"obj", "ply",  "stl", "gltf", "glb",    "bin",
                                                 "png", "node", "ele", "face", "damage", "vtk"};

bool isFrameName(const std::string& stem) {
  if (stem.size() != 11 || stem.rfind("frame_", 0) != 0) return false;
  return std::all_of(stem.begin() + 6, stem.end(), [](char c) { return std::isdigit(c); });
}

}  // namespace

bool isRunOutputName(const std::string& name) {
  if (name == "metrics.csv") return true;
  const size_t dot = name.find('.');
  if (dot == std::string::npos || name.find('.', dot + 1) != std::string::npos) return false;
  const std::string stem = name.substr(0, dot), extension = name.substr(dot + 1);
  if (!kOutputExtensions.count(extension)) return false;
  return stem == "final" || isFrameName(stem);
}

std::vector<std::string> runOutputsIn(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code kind;
    const std::string name = it->path().filename().string();
    if (isRunOutputName(name) && it->is_regular_file(kind)) names.push_back(name);
  }
  if (ec) throw OutputError("cannot list " + dir.string() + ": " + ec.message());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> clearRunOutputs(const fs::path& dir) {
  const std::vector<std::string> names = runOutputsIn(dir);
  for (const std::string& name : names) {
    std::error_code ec;
    if (!fs::remove(dir / name, ec) || ec) {
      throw OutputError("cannot remove " + (dir / name).string() + " left by an earlier run: " +
                        (ec ? ec.message() : std::string("not removed")));
    }
  }
  return names;
}

std::string describeWritten(std::vector<std::string> names) {
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  std::string plain;
  std::map<std::string, std::vector<std::string>> frames;  // extension -> names
  for (const std::string& name : names) {
    const size_t dot = name.find('.');
    if (dot != std::string::npos && isFrameName(name.substr(0, dot))) {
      frames[name.substr(dot + 1)].push_back(name);
      continue;
    }
    plain += (plain.empty() ? "" : ", ") + name;
  }
  for (const auto& [extension, list] : frames) {
    plain += (plain.empty() ? "" : ", ") + std::to_string(list.size()) + " frame_*." + extension;
    plain += list.size() == 1 ? " (" + list.front() + ")"
                              : " (" + list.front() + " .. " + list.back() + ")";
  }
  return plain;
}

}  // namespace galsculpt
