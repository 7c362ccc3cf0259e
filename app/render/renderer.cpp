#include "app/render/renderer.h"

#include <algorithm>
#include <cmath>

#include "app/render/gl.h"
#include "app/render/shader_sources.h"

namespace galsculpt {

namespace {

unsigned compile(GLenum type, const char* source, std::string* error) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    if (error) *error = std::string("shader compilation failed: ") + log;
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

unsigned link(const char* vertex, const char* fragment, std::string* error) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex, error);
  if (!vs) return 0;
  const GLuint fs = compile(GL_FRAGMENT_SHADER, fragment, error);
  if (!fs) {
    glDeleteShader(vs);
    return 0;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    if (error) *error = std::string("shader link failed: ") + log;
    glDeleteProgram(program);
    return 0;
  }
  return program;
}

}  // namespace

Renderer::~Renderer() {
  // Only release when a context was ever used (init succeeded).
  if (meshProgram_) {
    glDeleteProgram(meshProgram_);
    glDeleteBuffers(4, buffers_);
    glDeleteVertexArrays(1, &vao_);
    glDeleteBuffers(1, &pointBuffer_);
    glDeleteVertexArrays(1, &pointVao_);
    releaseTarget();
  }
}

void Renderer::releaseTarget() {
  if (!framebuffer_) return;
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteTextures(1, &colorTexture_);
  glDeleteRenderbuffers(1, &depthBuffer_);
  framebuffer_ = colorTexture_ = depthBuffer_ = 0;
  targetWidth_ = targetHeight_ = 0;
}

bool Renderer::init(std::string* error) {
  meshProgram_ = link(shaders::kMeshVert, shaders::kMeshFrag, error);
  if (!meshProgram_) return false;
  glGenVertexArrays(1, &vao_);
  glGenBuffers(4, buffers_);
  glGenVertexArrays(1, &pointVao_);
  glGenBuffers(1, &pointBuffer_);
  return true;
}

void Renderer::setMesh(const RenderMesh& mesh) {
  glBindVertexArray(vao_);
  const std::vector<float>* attributes[3] = {&mesh.positions, &mesh.normals, &mesh.colors};
  for (int a = 0; a < 3; ++a) {
    glBindBuffer(GL_ARRAY_BUFFER, buffers_[a]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(attributes[a]->size() * sizeof(float)),
                 attributes[a]->data(), GL_DYNAMIC_DRAW);
    glEnableVertexAttribArray(a);
    glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers_[3]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(unsigned)), mesh.indices.data(),
               GL_DYNAMIC_DRAW);
  glBindVertexArray(0);
  indexCount_ = static_cast<int>(mesh.indices.size());
  meshBox_.setEmpty();
  for (size_t i = 0; i + 2 < mesh.positions.size(); i += 3)
    meshBox_.extend(
        Eigen::Vector3f(mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2]));
  sceneChanged_ = true;
}

void Renderer::setPoints(const std::vector<Vec3>& points, const Vec3& color) {
  std::vector<float> data;
  data.reserve(3 * points.size());
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) data.push_back(static_cast<float>(p[k]));
  glBindVertexArray(pointVao_);
  glBindBuffer(GL_ARRAY_BUFFER, pointBuffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(),
               GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
  pointCount_ = static_cast<int>(points.size());
  pointColor_ = color;
  pointBox_.setEmpty();
  for (const Vec3& p : points) pointBox_.extend(p.cast<float>());
  sceneChanged_ = true;
}

void Renderer::setCached(bool cached) {
  cached_ = cached;
  sceneChanged_ = true;
  if (!cached_ && meshProgram_) releaseTarget();
}

bool Renderer::ensureTarget(int width, int height) {
  if (framebuffer_ && width == targetWidth_ && height == targetHeight_) return true;
  releaseTarget();
  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glGenTextures(1, &colorTexture_);
  glBindTexture(GL_TEXTURE_2D, colorTexture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colorTexture_, 0);
  glGenRenderbuffers(1, &depthBuffer_);
  glBindRenderbuffer(GL_RENDERBUFFER, depthBuffer_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer_);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) {
    releaseTarget();
    return false;
  }
  targetWidth_ = width;
  targetHeight_ = height;
  return true;
}

void Renderer::draw(const OrbitCamera& camera, int width, int height,
                    const RenderOptions& options) {
  if (!cached_) {
    drawScene(camera, width, height, options, PixelRect{0, 0, width, height});
    return;
  }
  PixelRect changed;
  if (update(camera, width, height, options, &changed)) present({PixelRect{0, 0, width, height}});
}

bool Renderer::update(const OrbitCamera& camera, int width, int height,
                      const RenderOptions& options, PixelRect* changed) {
  *changed = {};
  GLint screen = 0;  // where the caller draws: the window's framebuffer, or a test's
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &screen);
  // The scene is drawn into its own target when it changed (a new surface or anchors, the
  // camera, the size, the options) and copied to the screen at every draw: the window redraws
  // for its panels and cursor far more often than the scene changes.
  const Eigen::Matrix4f view = camera.view();
  const Eigen::Matrix4f projection =
      camera.projection(static_cast<double>(width) / std::max(height, 1));
  const bool sameView = framebuffer_ && width == targetWidth_ && height == targetHeight_ &&
                        view == cachedView_ && projection == cachedProjection_ &&
                        options.wireframe == cachedOptions_.wireframe &&
                        options.pointSize == cachedOptions_.pointSize;
  if (sameView && !sceneChanged_) return true;
  if (!ensureTarget(width, height)) {  // no target here: draw straight to the screen
    cached_ = false;
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(screen));
    drawScene(camera, width, height, options, PixelRect{0, 0, width, height});
    return false;
  }
  // Only the surface or the points changed: the rest of the picture is the same background,
  // so only where they were and where they are now is drawn again.
  const PixelRect extent = screenExtent(projection * view, width, height, options.pointSize);
  const PixelRect part = sameView ? cachedExtent_.united(extent).clipped(width, height)
                                  : PixelRect{0, 0, width, height};
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  drawScene(camera, width, height, options, part);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(screen));
  ++sceneRenders_;
  sceneChanged_ = false;
  cachedView_ = view;
  cachedProjection_ = projection;
  cachedOptions_ = options;
  cachedExtent_ = extent;
  *changed = part;
  return true;
}

void Renderer::present(const std::vector<PixelRect>& parts) {
  GLint screen = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &screen);
  glDisable(GL_SCISSOR_TEST);  // it would clip the copy
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(screen));
  for (const PixelRect& r : parts) {
    const PixelRect p = r.clipped(targetWidth_, targetHeight_);
    if (!p.empty())
      glBlitFramebuffer(p.x0, p.y0, p.x1, p.y1, p.x0, p.y0, p.x1, p.y1, GL_COLOR_BUFFER_BIT,
                        GL_NEAREST);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(screen));
}

PixelRect Renderer::screenExtent(const Eigen::Matrix4f& viewProjection, int width, int height,
                                 float pointSize) const {
  Eigen::AlignedBox3f box = meshBox_;
  if (pointCount_ > 0) box.extend(pointBox_);
  if (box.isEmpty() || indexCount_ + pointCount_ == 0) return {};
  const PixelRect full{0, 0, width, height};
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector4f p =
        viewProjection * box.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c)).homogeneous();
    if (p.w() < 1e-6f) return full;  // a corner behind the eye: it may cover anything
    const float x = (p.x() / p.w() * 0.5f + 0.5f) * width;
    const float y = (p.y() / p.w() * 0.5f + 0.5f) * height;
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  if (x1 < 0.0f || y1 < 0.0f || x0 > width || y0 > height) return {};
  // Grown by a point's radius and two pixels of rasterization slack.
  const int margin = static_cast<int>(std::ceil(pointSize)) + 2;
  const auto clampInt = [](float v) { return static_cast<int>(std::clamp(v, -1e6f, 1e6f)); };
  return PixelRect{clampInt(std::floor(x0)), clampInt(std::floor(y0)), clampInt(std::ceil(x1)),
                   clampInt(std::ceil(y1))}
      .grown(margin)
      .clipped(width, height);
}

void Renderer::drawBackground(int height, const PixelRect& part) {
  // A vertical gradient as horizontal bands of cleared colour, about one band per 8-bit level
  // of the gradient: a clear costs a software rasterizer a fraction of a shaded full-screen
  // pass, and on a GPU nothing.
  const Eigen::Vector3f top(0.32f, 0.36f, 0.42f), bottom(0.09f, 0.10f, 0.12f);
  const int bands = std::clamp(height / 4, 1, 96);
  glEnable(GL_SCISSOR_TEST);
  for (int b = 0; b < bands; ++b) {
    const PixelRect band{part.x0, std::max(part.y0, b * height / bands), part.x1,
                         std::min(part.y1, (b + 1) * height / bands)};
    if (band.empty()) continue;
    const float t = (b + 0.5f) / bands;  // 0 at the bottom row, as GL counts rows
    const Eigen::Vector3f c = bottom + t * (top - bottom);
    glScissor(band.x0, band.y0, band.x1 - band.x0, band.y1 - band.y0);
    glClearColor(c.x(), c.y(), c.z(), 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glScissor(part.x0, part.y0, part.x1 - part.x0, part.y1 - part.y0);
}

void Renderer::drawScene(const OrbitCamera& camera, int width, int height,
                         const RenderOptions& options, const PixelRect& part) {
  glViewport(0, 0, width, height);
  // Everything below stays within `part` (the scissor drawBackground leaves set).
  glEnable(GL_SCISSOR_TEST);
  glScissor(part.x0, part.y0, part.x1 - part.x0, part.y1 - part.y0);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  drawBackground(height, part);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);

  if (indexCount_ == 0) {
    glDisable(GL_SCISSOR_TEST);
    return;
  }
  glUseProgram(meshProgram_);
  const Eigen::Matrix4f view = camera.view();
  const Eigen::Matrix4f projection =
      camera.projection(static_cast<double>(width) / std::max(height, 1));
  glUniformMatrix4fv(glGetUniformLocation(meshProgram_, "uView"), 1, GL_FALSE, view.data());
  glUniformMatrix4fv(glGetUniformLocation(meshProgram_, "uProjection"), 1, GL_FALSE,
                     projection.data());
  glUniform3f(glGetUniformLocation(meshProgram_, "uKeyLightDir"), 0.4f, 0.7f, 0.6f);
  glUniform3f(glGetUniformLocation(meshProgram_, "uFillLightDir"), -0.6f, 0.2f, 0.4f);
  glUniform1f(glGetUniformLocation(meshProgram_, "uWireframe"), 0.0f);
  glUniform1f(glGetUniformLocation(meshProgram_, "uPointSize"), options.pointSize);
  glBindVertexArray(vao_);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
  glDisable(GL_POLYGON_OFFSET_FILL);
  if (options.wireframe) {
    glUniform1f(glGetUniformLocation(meshProgram_, "uWireframe"), 1.0f);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  if (pointCount_ > 0) {
    // Flat colour; the surface is drawn with a polygon offset, so dots on it pass the depth test
    // and those inside the body stay hidden.
    glUniform1f(glGetUniformLocation(meshProgram_, "uWireframe"), 2.0f);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glBindVertexArray(pointVao_);
    glVertexAttrib3f(1, 0.0f, 0.0f, 1.0f);
    glVertexAttrib3f(2, static_cast<float>(pointColor_.x()), static_cast<float>(pointColor_.y()),
                     static_cast<float>(pointColor_.z()));
    glDrawArrays(GL_POINTS, 0, pointCount_);
    glDisable(GL_PROGRAM_POINT_SIZE);
  }
  glBindVertexArray(0);
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace galsculpt
