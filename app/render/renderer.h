// Draws a surface with a background gradient. One renderer serves the GLFW window and the
// offscreen EGL context: it needs only a current OpenGL 3.3 core context.
//
// Cached (setCached), the scene is drawn into a texture of its own only when it changed and
// copied to the screen at every draw: for a software rasterizer, where shading the scene is
// most of what a window draw costs and the window redraws for its panels and cursor far more
// often than the simulation delivers a new surface.
#pragma once

#include <string>
#include <vector>

#include "app/render/pixel_rect.h"
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
  // Into the framebuffer bound now.
  void draw(const OrbitCamera& camera, int width, int height, const RenderOptions& options = {});
  void setCached(bool cached);
  bool cached() const { return cached_; }
  // How many times the scene was drawn into the cache (cached draws that only copied it do not
  // count).
  int sceneRenders() const { return sceneRenders_; }

  // Cached, in two steps, for a caller that redraws only what changed (a window whose back
  // buffer still holds its previous draw): update() brings the cache up to date and returns
  // where on the screen the scene changed since the previous update (empty: nowhere; when only
  // the surface or the points changed, the screen rectangle of their old and new extent, and
  // only that part of the cache is drawn again); present() then copies the given parts of the
  // cache to the framebuffer bound now. False from update() when there is no cache here (draw()
  // then draws straight to the screen).
  bool update(const OrbitCamera& camera, int width, int height, const RenderOptions& options,
              PixelRect* changed);
  void present(const std::vector<PixelRect>& parts);

 private:
  void drawScene(const OrbitCamera& camera, int width, int height, const RenderOptions& options,
                 const PixelRect& part);
  void drawBackground(int height, const PixelRect& part);
  // Where the surface and the points lie on the screen (grown by the points' size).
  PixelRect screenExtent(const Eigen::Matrix4f& viewProjection, int width, int height,
                         float pointSize) const;
  bool ensureTarget(int width, int height);
  void releaseTarget();

  unsigned meshProgram_ = 0;
  unsigned vao_ = 0, buffers_[4] = {0, 0, 0, 0};
  unsigned pointVao_ = 0, pointBuffer_ = 0;
  int indexCount_ = 0, pointCount_ = 0;
  Vec3 pointColor_ = Vec3::Zero();
  Eigen::AlignedBox3f meshBox_, pointBox_;  // world extents of what setMesh and setPoints gave

  bool cached_ = false, sceneChanged_ = true;
  unsigned framebuffer_ = 0, colorTexture_ = 0, depthBuffer_ = 0;
  int targetWidth_ = 0, targetHeight_ = 0, sceneRenders_ = 0;
  Eigen::Matrix4f cachedView_ = Eigen::Matrix4f::Zero(), cachedProjection_ = cachedView_;
  RenderOptions cachedOptions_;
  PixelRect cachedExtent_;  // where the scene in the cache has its surface and points
};

}  // namespace galsculpt
