// What `open` and `render` show: a surface, a title and a few facts for the overlay.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct ViewContent {
  std::string title;
  TriMesh surface;
  std::vector<std::string> facts;  // "12345 tets", "material: rubber", ...
};

// Loads a project (.gsproj), a scene (.json), a tet mesh or a surface mesh for viewing; progress
// goes to `log`.
ViewContent loadViewContent(const std::filesystem::path& file, std::ostream& log);

// Renders standard views offscreen into `outDir`; returns the files written.
std::vector<std::string> renderViewsOffscreen(const ViewContent& content,
                                              const std::filesystem::path& outDir, int width,
                                              int height);

}  // namespace galsculpt
