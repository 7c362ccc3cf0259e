// PNG snapshots rendered offscreen (EGL, surfaceless Mesa: no display needed): one context and
// renderer, a mesh, and any number of camera poses. Used by `render`/`open --headless` (the
// standard views) and by `run`/`play --png-every` (frames of a simulation).
#pragma once

#include <filesystem>
#include <memory>

#include "app/render/offscreen_context.h"
#include "app/render/render_mesh.h"
#include "app/render/renderer.h"
#include "app/window/camera.h"

namespace galsculpt {

class SnapshotRenderer {
 public:
  // Throws std::runtime_error (with the reason) when no offscreen context can be made.
  SnapshotRenderer(int width, int height);
  void setMesh(const RenderMesh& mesh) { renderer_.setMesh(mesh); }
  void setPoints(const std::vector<Vec3>& points, const Vec3& color) {
    renderer_.setPoints(points, color);
  }
  // Renders the mesh from `camera` and writes the PNG atomically (OutputError on failure).
  void write(const OrbitCamera& camera, const std::filesystem::path& file);

 private:
  int width_, height_;
  std::unique_ptr<OffscreenContext> context_;
  Renderer renderer_;
};

}  // namespace galsculpt
