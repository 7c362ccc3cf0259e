#include "app/render_mesh.h"

#include <gtest/gtest.h>

#include "engine/scene_mesh.h"
#include "engine/simulation.h"
#include "solver/knife.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

TEST(HeatColor, RunsFromBlueToRedAndClamps) {
  EXPECT_GT(heatColor(0.0).z(), 0.8);
  EXPECT_GT(heatColor(1.0).x(), 0.8);
  EXPECT_EQ(heatColor(-3.0), heatColor(0.0));
  EXPECT_EQ(heatColor(7.0), heatColor(1.0));
  EXPECT_EQ(heatColor(std::nan("")), heatColor(0.0));
  for (double t = 0.0; t < 1.0; t += 0.01)
    EXPECT_LT((heatColor(t + 0.01) - heatColor(t)).norm(), 0.1) << "continuous at " << t;
}

// The damage view colours the faces around a cut hot and the untouched surface cold; the
// geometry is the shaded view's.
TEST(SurfaceViews, DamageViewMarksTheCutAndKeepsTheGeometry) {
  const SceneDescription scene =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  Simulation sim(scene, loadSceneMesh(scene));
  sim.cut(sweptBladeSurface(Vec3(0, 0.3, -0.3), Vec3(0, 0.3, 0.3), Vec3(0, 0.05, -0.3),
                            Vec3(0, 0.05, 0.3)));
  const VisualSurface& surface = sim.surface();
  const RenderMesh shaded = makeRenderMesh(surface, SurfaceStyle{}, {});
  SurfaceStyle damageStyle;
  damageStyle.view = SurfaceView::Damage;
  damageStyle.tintCracks = false;
  const RenderMesh damage = makeRenderMesh(surface, damageStyle, sim.vertexDamage());
  EXPECT_EQ(damage.positions, shaded.positions);
  EXPECT_EQ(damage.indices, shaded.indices);
  int hot = 0, cold = 0;
  for (size_t i = 0; i < damage.colors.size() / 3; ++i) {
    const Vec3 c(damage.colors[3 * i], damage.colors[3 * i + 1], damage.colors[3 * i + 2]);
    const double y = damage.positions[3 * i + 1];
    if (y < -0.05) cold += (c - heatColor(0.0)).norm() < 1e-6;  // far below the cut
    if ((c - heatColor(0.0)).norm() > 0.2) ++hot;
  }
  EXPECT_GT(hot, 10) << "damaged vertices show warmer than the cold blue";
  EXPECT_GT(cold, 50) << "the untouched bottom shows cold";
}

}  // namespace
}  // namespace galsculpt
