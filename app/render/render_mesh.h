// GPU-ready triangle data: positions, smooth normals and colours, flattened to floats.
#pragma once

#include <vector>

#include "engine/surface/surface_builder.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// The body's colour and the tint of crack faces (linear RGB).
inline const Vec3 kSurfaceColor(0.80, 0.55, 0.42);
inline const Vec3 kCrackColor(0.75, 0.12, 0.10);
inline const Vec3 kAnchorColor(0.15, 0.35, 1.0);  // anchored vertices, blue as in the paper

struct RenderMesh {
  std::vector<float> positions;   // (3 nVerts)
  std::vector<float> normals;     // (3 nVerts)
  std::vector<float> colors;      // (3 nVerts), linear RGB
  std::vector<unsigned> indices;  // (3 nTris)
};

RenderMesh makeRenderMesh(const TriMesh& mesh, const Vec3& color);

// The visualization surface with crack faces tinted: each tag gets its own vertices, so normals
// are sharp where crack faces meet the outer surface; outer faces are shaded smooth, crack
// faces flat (each face its own three vertices and normal).
RenderMesh makeRenderMesh(const VisualSurface& surface, const Vec3& outerColor,
                          const Vec3& crackColor);

// What the surface's colour shows: the material, each vertex's damage (fraction of its
// edges broken), or its stress (a heat map up to `scaleMax`).
enum class SurfaceView { Shaded, Damage, Stress };
struct SurfaceStyle {
  SurfaceView view = SurfaceView::Shaded;
  bool tintCracks = true;
  double scaleMax = 1.0;  // the value shown as the hottest colour
};
// `values`: one per tet-mesh vertex (Damage, Stress); a surface vertex shows the mean over the
// faces around it of their cell vertex's value.
RenderMesh makeRenderMesh(const VisualSurface& surface, const SurfaceStyle& style,
                          const std::vector<double>& values);
// Blue - cyan - green - yellow - red for t in [0, 1] (clamped).
Vec3 heatColor(double t);

}  // namespace galsculpt
