// Headless OpenGL: an EGL context with no window (Mesa's surfaceless platform, no X, no
// /dev/dri needed) rendering into a multisampled framebuffer object.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace galsculpt {

class OffscreenContext {
 public:
  // nullptr (with a reason) when no EGL/OpenGL 3.3 core context can be made.
  static std::unique_ptr<OffscreenContext> create(int width, int height, std::string* error);
  ~OffscreenContext();

  int width() const { return width_; }
  int height() const { return height_; }
  // Binds the framebuffer to render into.
  void bind();
  // Resolves the multisampled image; returns RGBA rows, top row first.
  std::vector<std::uint8_t> readPixels();
  std::string rendererName() const;

 private:
  OffscreenContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  int width_ = 0, height_ = 0;
  unsigned msFbo_ = 0, msColor_ = 0, msDepth_ = 0, fbo_ = 0, color_ = 0;
};

// RGBA rows as OpenGL reads them (the bottom one first) in image order (the top one first).
std::vector<std::uint8_t> topRowFirst(const std::vector<std::uint8_t>& rgba, int width, int height);

// Writes RGBA pixels as PNG, atomically. Throws OutputError.
void writePng(const std::string& path, int width, int height,
              const std::vector<std::uint8_t>& rgba);

}  // namespace galsculpt
