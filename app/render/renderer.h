// Draws a surface with a background gradient. One renderer serves the GLFW window and the
// offscreen EGL context: it needs only a current OpenGL 3.3 core context.
#pragma once

#include <string>
#include <vector>

#include "app/render/render_mesh.h"
#include "app/window/camera.h"

namespace galsculpt {

struct RenderOptions {
  bool wireframe = false;  // draw edges over the shaded surface
  float pointSize = 6.0f;  // pixels, for the points of setPoints
};

class Renderer {
 public:
  Renderer() = default;
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Compiles the shaders; false (with a reason) when the context cannot run them.
  bool init(std::string* error);
  void setMesh(const RenderMesh& mesh);
  // Marked vertices (anchors: blue, as in the paper), drawn as dots over the surface.
  void setPoints(const std::vector<Vec3>& points, const Vec3& color);
  void draw(const OrbitCamera& camera, int width, int height, const RenderOptions& options = {});

 private:
  unsigned meshProgram_ = 0, backgroundProgram_ = 0;
  unsigned vao_ = 0, emptyVao_ = 0, buffers_[4] = {0, 0, 0, 0};
  unsigned pointVao_ = 0, pointBuffer_ = 0;
  int indexCount_ = 0, pointCount_ = 0;
  Vec3 pointColor_ = Vec3::Zero();
};

}  // namespace galsculpt
