#include "app/render/renderer.h"

#include <algorithm>

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
    glDeleteProgram(backgroundProgram_);
    glDeleteBuffers(4, buffers_);
    glDeleteVertexArrays(1, &vao_);
    glDeleteVertexArrays(1, &emptyVao_);
    glDeleteBuffers(1, &pointBuffer_);
    glDeleteVertexArrays(1, &pointVao_);
  }
}

bool Renderer::init(std::string* error) {
  meshProgram_ = link(shaders::kMeshVert, shaders::kMeshFrag, error);
  if (!meshProgram_) return false;
  backgroundProgram_ = link(shaders::kBackgroundVert, shaders::kBackgroundFrag, error);
  if (!backgroundProgram_) return false;
  glGenVertexArrays(1, &vao_);
  glGenVertexArrays(1, &emptyVao_);
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
}

void Renderer::draw(const OrbitCamera& camera, int width, int height,
                    const RenderOptions& options) {
  glViewport(0, 0, width, height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);

  glUseProgram(backgroundProgram_);
  glUniform3f(glGetUniformLocation(backgroundProgram_, "uTop"), 0.32f, 0.36f, 0.42f);
  glUniform3f(glGetUniformLocation(backgroundProgram_, "uBottom"), 0.09f, 0.10f, 0.12f);
  glBindVertexArray(emptyVao_);
  glDepthMask(GL_FALSE);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);

  if (indexCount_ == 0) return;
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
}

}  // namespace galsculpt
