// Offscreen (EGL, surfaceless Mesa) rendering: what a person would see, checked by pixels.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace galsculpt
