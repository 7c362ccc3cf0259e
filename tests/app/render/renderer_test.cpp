// Offscreen (EGL, surfaceless Mesa) rendering: what a person would see, checked by pixels.
#include <gtest/gtest.h>

#include "app/render/gl.h"
#include "app/render/offscreen_context.h"
#include "app/render/render_mesh.h"
#include "app/render/renderer.h"
#include "app/render/view_content.h"
#include "app/window/camera.h"
#include "engine/surface/surface_builder.h"
#include "solver/fracture/knife.h"
#include "solver/mesh/shape_generators.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

struct Image {
  int width, height;
  std::vector<std::uint8_t> rgba;
  Eigen::Vector3i at(int x, int y) const {
    const size_t i = (static_cast<size_t>(y) * width + x) * 4;
    return Eigen::Vector3i(rgba[i], rgba[i + 1], rgba[i + 2]);
  }
};

// The object is orange-ish; the background is a grey-blue gradient (blue >= red).
bool isObject(const Eigen::Vector3i& c) {
  return c.x() > c.z() + 20;
}

Image renderSphere(OffscreenContext& ctx, Renderer& r, const TriMesh& mesh,
                   const OrbitCamera& camera) {
  r.setMesh(makeRenderMesh(mesh, Vec3(0.8, 0.55, 0.42)));
  ctx.bind();
  r.draw(camera, ctx.width(), ctx.height());
  return {ctx.width(), ctx.height(), ctx.readPixels()};
}

class RenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    ctx_ = OffscreenContext::create(160, 120, &error);
    ASSERT_TRUE(ctx_) << "EGL offscreen context: " << error;
    ASSERT_TRUE(renderer_.init(&error)) << error;
  }
  std::unique_ptr<OffscreenContext> ctx_;
  Renderer renderer_;
};

TEST_F(RenderTest, SphereCoversTheExpectedDiscAndIsLit) {
  const TriMesh sphere = makeIcosphere(1.0, 3);
  OrbitCamera camera;
  camera.distance = 4.0;
  camera.yaw = 0.0;
  camera.pitch = 0.0;
  const Image img = renderSphere(*ctx_, renderer_, sphere, camera);
  // Projected radius: f * r / sqrt(d^2 - r^2) in NDC, times half the height in pixels.
  const double f = 1.0 / std::tan(camera.fovY / 2.0);
  const double radiusPx = f / std::sqrt(15.0) * img.height / 2.0;
  int inside = 0, covered = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const bool obj = isObject(img.at(x, y));
      covered += obj;
      const double r = std::hypot(x + 0.5 - img.width / 2.0, y + 0.5 - img.height / 2.0);
      if (r < radiusPx - 1.5) {
        EXPECT_TRUE(obj) << "hole at " << x << "," << y;
      }
      if (r > radiusPx + 1.5) {
        EXPECT_FALSE(obj) << "spill at " << x << "," << y;
      }
      inside += (r < radiusPx);
    }
  }
  EXPECT_NEAR(covered, inside, 0.05 * inside);
  // Lit from the upper right: the upper-right of the disc is brighter than the lower-left.
  const int cx = img.width / 2, cy = img.height / 2, o = static_cast<int>(radiusPx * 0.5);
  EXPECT_GT(img.at(cx + o, cy - o).sum(), img.at(cx - o, cy + o).sum() + 30);
}

TEST_F(RenderTest, MovingTheObjectChangesTheImage) {
  OrbitCamera camera;
  camera.distance = 4.0;
  const TriMesh sphere = makeIcosphere(1.0, 2);
  const Image a = renderSphere(*ctx_, renderer_, sphere, camera);
  TriMesh moved = sphere;
  for (Vec3& v : moved.vertices) v.x() += 0.6;
  const Image b = renderSphere(*ctx_, renderer_, moved, camera);
  int changed = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) changed += (a.rgba[i] != b.rgba[i]);
  EXPECT_GT(changed, 500);
}

// OpenGL's rows come bottom first; an image's top first: the rows swap, each row kept whole.
TEST(TopRowFirst, SwapsTheRowsAndKeepsEachRow) {
  const std::vector<std::uint8_t> gl = {1,  2,  3,  4,  5,  6,  7,  8,    // bottom row
                                        9,  10, 11, 12, 13, 14, 15, 16,   // middle row
                                        17, 18, 19, 20, 21, 22, 23, 24};  // top row
  EXPECT_EQ(topRowFirst(gl, 2, 3),
            (std::vector<std::uint8_t>{17, 18, 19, 20, 21, 22, 23, 24, 9, 10, 11, 12,
                                       13, 14, 15, 16, 1,  2,  3,  4,  5, 6,  7,  8}));
}

TEST(RenderViews, WritesPngFiles) {
  test::TempDir dir;
  ViewContent content;
  content.title = "sphere";
  content.surface = makeIcosphere(0.1, 2);
  const auto files = renderViewsOffscreen(content, dir / "out", 64, 48);
  ASSERT_EQ(files.size(), 4u);
  for (const std::string& f : files) {
    const std::string png = test::readText(f);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
  }
}

// A bar cut in two, its right half moved away: the crack faces show, tinted.
TEST_F(RenderTest, CrackFacesAreTintedWhereACutOpens) {
  SimModel model = buildSimModel(test::gridBar(6, 2, 2, 0.1), MaterialParams{});
  SimState state = initialState(model);
  SurfaceBuilder builder(model);
  const Vec3 outer(0.8, 0.55, 0.42), crack(0.75, 0.12, 0.1);
  // Looking down into the gap, from beyond its far side: the near half's crack face shows.
  OrbitCamera camera;
  camera.target = Vec3(0.435, 0.1, 0.1);
  camera.distance = 1.6;
  camera.yaw = 0.6;
  camera.pitch = 0.9;
  auto crackPixels = [&] {
    builder.update(model, state);
    renderer_.setMesh(makeRenderMesh(builder.surface(), outer, crack));
    ctx_->bind();
    renderer_.draw(camera, ctx_->width(), ctx_->height());
    const Image img{ctx_->width(), ctx_->height(), ctx_->readPixels()};
    int n = 0;
    for (int y = 0; y < img.height; ++y) {
      for (int x = 0; x < img.width; ++x) {
        const Eigen::Vector3i c = img.at(x, y);
        // Red with little green: the crack tint (the outer colour keeps green near 0.7 red).
        n += c.x() > 60 && c.y() * 100 < c.x() * 55;
      }
    }
    return n;
  };
  EXPECT_EQ(crackPixels(), 0) << "no crack before the cut";
  cutAlongSurface(model, state,
                  sweptBladeSurface(Vec3(0.31, -1, -1), Vec3(0.31, -1, 1), Vec3(0.31, 1, -1),
                                    Vec3(0.31, 1, 1)));
  for (int v = 0; v < model.numVertices(); ++v) {
    if (model.mesh.vertices[v].x() > 0.31) state.x[v] += Vec3(0.25, 0, 0);
  }
  EXPECT_GT(crackPixels(), 40) << "the opened cut shows its crack faces";
}

// A plain (single-sample) framebuffer standing in for a window's: the cached renderer copies its
// scene into whatever framebuffer is bound when it draws.
class PlainTarget {
 public:
  PlainTarget(int width, int height) : width_(width), height_(height) {
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glGenTextures(1, &color_);
    glBindTexture(GL_TEXTURE_2D, color_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_, 0);
    glGenRenderbuffers(1, &depth_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  }
  ~PlainTarget() {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &color_);
    glDeleteRenderbuffers(1, &depth_);
  }
  Image draw(Renderer& r, const OrbitCamera& camera, const RenderOptions& options = {}) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    r.draw(camera, width_, height_, options);
    return read();
  }
  // As the window draws on a software rasterizer: the cache brought up to date, and only the
  // part that changed copied over what the target already shows.
  Image update(Renderer& r, const OrbitCamera& camera, PixelRect* changed) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    EXPECT_TRUE(r.update(camera, width_, height_, RenderOptions{}, changed));
    r.present({*changed});
    return read();
  }
  Image read() {
    Image img{width_, height_,
              std::vector<std::uint8_t>(4 * static_cast<size_t>(width_) * height_)};
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
    return img;
  }

 private:
  int width_, height_;
  unsigned fbo_ = 0, color_ = 0, depth_ = 0;
};

int differingPixels(const Image& a, const Image& b) {
  int n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) n += (a.at(x, y) - b.at(x, y)).cwiseAbs().maxCoeff() > 1;
  return n;
}

TEST_F(RenderTest, TheCachedSceneIsTheSceneAndFollowsEveryChange) {
  PlainTarget target(ctx_->width(), ctx_->height());
  OrbitCamera camera;
  camera.distance = 4.0;
  renderer_.setMesh(makeRenderMesh(makeIcosphere(1.0, 3), Vec3(0.8, 0.55, 0.42)));
  const Image direct = target.draw(renderer_, camera);
  renderer_.setCached(true);
  const Image cached = target.draw(renderer_, camera);
  EXPECT_EQ(differingPixels(direct, cached), 0) << "the cache holds what a direct draw shows";
  EXPECT_EQ(renderer_.sceneRenders(), 1);
  EXPECT_EQ(differingPixels(cached, target.draw(renderer_, camera)), 0);
  EXPECT_EQ(renderer_.sceneRenders(), 1) << "nothing changed: the cache is only copied";

  // Each change draws the scene again: the camera, the surface, the anchors, the options.
  camera.yaw += 0.3;
  camera.target.x() += 0.4;
  const Image moved = target.draw(renderer_, camera);
  EXPECT_EQ(renderer_.sceneRenders(), 2);
  EXPECT_GT(differingPixels(cached, moved), 100) << "the camera moved";
  renderer_.setMesh(makeRenderMesh(makeIcosphere(0.6, 3), Vec3(0.8, 0.55, 0.42)));
  const Image smaller = target.draw(renderer_, camera);
  EXPECT_GT(differingPixels(moved, smaller), 100) << "the surface changed";
  renderer_.setPoints({Vec3(0.0, 0.0, 0.6), Vec3(0.1, 0.1, 0.58)}, Vec3(0.0, 0.0, 1.0));
  const Image dotted = target.draw(renderer_, camera);
  EXPECT_GT(differingPixels(smaller, dotted), 0) << "the anchors appeared";
  EXPECT_EQ(renderer_.sceneRenders(), 4);
  const Image wire = target.draw(renderer_, camera, RenderOptions{true, 6.0f});
  EXPECT_GT(differingPixels(dotted, wire), 100) << "the wireframe on";
  EXPECT_EQ(renderer_.sceneRenders(), 5);

  renderer_.setCached(false);
  EXPECT_EQ(differingPixels(dotted, target.draw(renderer_, camera)), 0) << "drawn directly again";
}

// When only the surface or the points change, only their old and new extent on the screen is
// drawn again, and only that part is copied over the previous picture: the result is the
// picture a full draw of the new state gives, pixel for pixel.
TEST_F(RenderTest, APartialRedrawIsTheFullPictureOfTheNewState) {
  PlainTarget target(ctx_->width(), ctx_->height());
  OrbitCamera camera;
  camera.distance = 4.0;
  Renderer fresh;
  std::string error;
  ASSERT_TRUE(fresh.init(&error)) << error;
  const auto ball = [](double r, const Vec3& at) {
    TriMesh m = makeIcosphere(r, 3);
    for (Vec3& v : m.vertices) v += at;
    return makeRenderMesh(m, Vec3(0.8, 0.55, 0.42));
  };
  renderer_.setCached(true);
  renderer_.setMesh(ball(0.5, Vec3(-0.6, 0.0, 0.0)));
  PixelRect changed;
  target.update(renderer_, camera, &changed);
  EXPECT_EQ(changed, (PixelRect{0, 0, ctx_->width(), ctx_->height()})) << "the first: everything";
  EXPECT_TRUE(renderer_.update(camera, ctx_->width(), ctx_->height(), {}, &changed));
  EXPECT_TRUE(changed.empty()) << "nothing changed";
  struct Step {
    RenderMesh mesh;
    std::vector<Vec3> points;
  };
  const std::vector<Step> steps = {{ball(0.4, Vec3(-0.5, 0.1, 0.0)), {}},
                                   {ball(0.4, Vec3(-0.5, 0.1, 0.0)), {Vec3(-0.5, 0.1, 0.4)}},
                                   {ball(0.3, Vec3(0.6, -0.2, 0.0)), {Vec3(0.6, -0.2, 0.3)}},
                                   {RenderMesh{}, {}}};
  for (size_t i = 0; i < steps.size(); ++i) {
    renderer_.setMesh(steps[i].mesh);
    renderer_.setPoints(steps[i].points, Vec3(0.0, 0.0, 1.0));
    const Image partial = target.update(renderer_, camera, &changed);
    EXPECT_FALSE(changed.empty()) << "step " << i;
    EXPECT_LT(changed.area(), static_cast<long>(ctx_->width()) * ctx_->height())
        << "step " << i << ": only part of the picture";
    fresh.setMesh(steps[i].mesh);
    fresh.setPoints(steps[i].points, Vec3(0.0, 0.0, 1.0));
    EXPECT_EQ(differingPixels(partial, target.draw(fresh, camera)), 0) << "step " << i;
  }
}

}  // namespace
}  // namespace galsculpt
