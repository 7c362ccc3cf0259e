// Draws a surface with a background gradient. One renderer serves the GLFW window and the
// offscreen EGL context: it needs only a current OpenGL 3.3 core context.
#pragma once

#include <string>

#include "app/camera.h"
#include "app/render_mesh.h"

namespace galsculpt {

struct RenderOptions {
  bool wireframe = false;  // draw edges over the shaded surface
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
  void draw(const OrbitCamera& camera, int width, int height, const RenderOptions& options = {});

 private:
  unsigned meshProgram_ = 0, backgroundProgram_ = 0;
  unsigned vao_ = 0, emptyVao_ = 0, buffers_[4] = {0, 0, 0, 0};
  int indexCount_ = 0;
};

}  // namespace galsculpt
