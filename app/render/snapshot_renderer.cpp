#include "app/render/snapshot_renderer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace galsculpt {

SnapshotRenderer::SnapshotRenderer(int width, int height) : width_(width), height_(height) {
  std::string error;
  context_ = OffscreenContext::create(width, height, &error);
  if (!context_) throw std::runtime_error("offscreen rendering unavailable: " + error);
  if (!renderer_.init(&error)) throw std::runtime_error(error);
}

void SnapshotRenderer::write(const OrbitCamera& camera, const std::filesystem::path& file) {
  context_->bind();
  // Anchor dots about as large relative to the image as in the window.
  renderer_.draw(camera, width_, height_,
                 RenderOptions{false, std::max(2.0f, static_cast<float>(width_) / 320.0f)});
  writePng(file.string(), width_, height_, context_->readPixels());
}

}  // namespace galsculpt
