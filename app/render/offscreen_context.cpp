#include "app/render/offscreen_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <stb/stb_image_write.h>
#include <cstring>

#include "app/render/gl.h"
#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace {
constexpr int kSamples = 4;

EGLDisplay surfacelessDisplay() {
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (getPlatformDisplay) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) return d;
  }
  return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}
}  // namespace

std::unique_ptr<OffscreenContext> OffscreenContext::create(int width, int height,
                                                           std::string* error) {
  auto fail = [&](const std::string& why) -> std::unique_ptr<OffscreenContext> {
    if (error) *error = why;
    return nullptr;
  };
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    return fail("invalid image size");
  EGLDisplay display = surfacelessDisplay();
  if (display == EGL_NO_DISPLAY) return fail("no EGL display");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) return fail("eglInitialize failed");
  if (!eglBindAPI(EGL_OPENGL_API)) return fail("EGL has no desktop OpenGL");
  // The default surface type is "window", which a surfaceless display has none of.
  const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                  EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config;
  EGLint count = 0;
  if (!eglChooseConfig(display, configAttribs, &config, 1, &count) || count == 0) {
    return fail("no EGL config for OpenGL");
  }
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                   3,
                                   EGL_CONTEXT_MINOR_VERSION,
                                   3,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                   EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                   EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
  if (context == EGL_NO_CONTEXT) return fail("cannot create an OpenGL 3.3 core context");
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    return fail("eglMakeCurrent failed (no surfaceless support)");
  }

  std::unique_ptr<OffscreenContext> ctx(new OffscreenContext());
  ctx->display_ = display;
  ctx->context_ = context;
  ctx->width_ = width;
  ctx->height_ = height;
  glGenFramebuffers(1, &ctx->msFbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, ctx->msFbo_);
  glGenRenderbuffers(1, &ctx->msColor_);
  glBindRenderbuffer(GL_RENDERBUFFER, ctx->msColor_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, kSamples, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ctx->msColor_);
  glGenRenderbuffers(1, &ctx->msDepth_);
  glBindRenderbuffer(GL_RENDERBUFFER, ctx->msDepth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, kSamples, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, ctx->msDepth_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    return fail("multisampled framebuffer incomplete");
  }
  glGenFramebuffers(1, &ctx->fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, ctx->fbo_);
  glGenRenderbuffers(1, &ctx->color_);
  glBindRenderbuffer(GL_RENDERBUFFER, ctx->color_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ctx->color_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    return fail("framebuffer incomplete");
  }
  ctx->bind();
  return ctx;
}

OffscreenContext::~OffscreenContext() {
  if (!context_) return;
  glDeleteFramebuffers(1, &msFbo_);
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &msColor_);
  glDeleteRenderbuffers(1, &msDepth_);
  glDeleteRenderbuffers(1, &color_);
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

void OffscreenContext::bind() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_);
  glBindFramebuffer(GL_FRAMEBUFFER, msFbo_);
}

std::vector<std::uint8_t> OffscreenContext::readPixels() {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, msFbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  std::vector<std::uint8_t> pixels(static_cast<size_t>(width_) * height_ * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glBindFramebuffer(GL_FRAMEBUFFER, msFbo_);
  return topRowFirst(pixels, width_, height_);
}

std::vector<std::uint8_t> topRowFirst(const std::vector<std::uint8_t>& rgba, int width,
                                      int height) {
  const size_t row = static_cast<size_t>(width) * 4;
  std::vector<std::uint8_t> flipped(rgba.size());
  for (int y = 0; y < height; ++y)
    std::memcpy(&flipped[static_cast<size_t>(y) * row],
                &rgba[static_cast<size_t>(height - 1 - y) * row], row);
  return flipped;
}

std::string OffscreenContext::rendererName() const {
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(name ? name : "?") + ", OpenGL " + (version ? version : "?");
}

void writePng(const std::string& path, int width, int height,
              const std::vector<std::uint8_t>& rgba) {
  writeFileAtomically(path, [&](std::ostream& out) {
    auto sink = [](void* context, void* data, int size) {
      static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
    };
    if (!stbi_write_png_to_func(sink, &out, width, height, 4, rgba.data(), width * 4)) {
      throw OutputError("cannot encode PNG " + path);
    }
  });
}

}  // namespace galsculpt
