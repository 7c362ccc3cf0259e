#include "app/render/render_mesh.h"

namespace galsculpt {

RenderMesh makeRenderMesh(const TriMesh& mesh, const Vec3& color) {
  RenderMesh r;
  const std::vector<Vec3> normals = vertexNormals(mesh);
  r.positions.reserve(mesh.vertices.size() * 3);
  r.normals.reserve(mesh.vertices.size() * 3);
  r.colors.reserve(mesh.vertices.size() * 3);
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      r.positions.push_back(static_cast<float>(mesh.vertices[i][k]));
      r.normals.push_back(static_cast<float>(normals[i][k]));
      r.colors.push_back(static_cast<float>(color[k]));
    }
  }
  r.indices.reserve(mesh.faces.size() * 3);
  for (const Tri& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) r.indices.push_back(static_cast<unsigned>(f[k]));
  }
  return r;
}

namespace {

// Appends the faces of one tag. Outer faces are smooth (shared vertices, area-weighted
// normals); crack faces are flat (three vertices a face, the face's own normal): a cut is a
// plane the blade left, and smoothing across its facets would round the cut's edges off.
// `colorOf` gives each surface vertex's colour.
template <typename ColorOf>
void appendTag(RenderMesh& out, const VisualSurface& surface, SurfaceTag tag, ColorOf colorOf) {
  std::vector<int> source;
  const TriMesh part = facesWithTag(surface, tag, &source);
  const unsigned base = static_cast<unsigned>(out.positions.size() / 3);
  auto push = [&](const Vec3& p, const Vec3& n, const Vec3& c) {
    for (int k = 0; k < 3; ++k) {
      out.positions.push_back(static_cast<float>(p[k]));
      out.normals.push_back(static_cast<float>(n[k]));
      out.colors.push_back(static_cast<float>(c[k]));
    }
  };
  if (tag == SurfaceTag::Outer) {
    const std::vector<Vec3> normals = vertexNormals(part);
    for (size_t i = 0; i < part.vertices.size(); ++i)
      push(part.vertices[i], normals[i], colorOf(source[i]));
    for (const Tri& f : part.faces)
      for (int k = 0; k < 3; ++k) out.indices.push_back(base + static_cast<unsigned>(f[k]));
    return;
  }
  unsigned next = base;
  for (const Tri& f : part.faces) {
    const Vec3 n = (part.vertices[f[1]] - part.vertices[f[0]])
                       .cross(part.vertices[f[2]] - part.vertices[f[0]])
                       .stableNormalized();
    for (int k = 0; k < 3; ++k) {
      push(part.vertices[f[k]], n, colorOf(source[f[k]]));
      out.indices.push_back(next++);
    }
  }
}

}  // namespace

RenderMesh makeRenderMesh(const VisualSurface& surface, const Vec3& outerColor,
                          const Vec3& crackColor) {
  RenderMesh out;
  appendTag(out, surface, SurfaceTag::Outer, [&](int) { return outerColor; });
  appendTag(out, surface, SurfaceTag::Crack, [&](int) { return crackColor; });
  return out;
}

Vec3 heatColor(double t) {
  static const Vec3 stops[] = {Vec3(0.10, 0.20, 0.85), Vec3(0.10, 0.75, 0.85),
                               Vec3(0.15, 0.80, 0.20), Vec3(0.95, 0.85, 0.10),
                               Vec3(0.90, 0.12, 0.08)};
  if (!(t > 0.0)) return stops[0];
  if (t >= 1.0) return stops[4];
  const double s = t * 4.0;
  const int i = static_cast<int>(s);
  return (1.0 - (s - i)) * stops[i] + (s - i) * stops[i + 1];
}

RenderMesh makeRenderMesh(const VisualSurface& surface, const SurfaceStyle& style,
                          const std::vector<double>& values) {
  const Vec3 crackColor = style.tintCracks ? kCrackColor : kSurfaceColor;
  if (style.view == SurfaceView::Shaded) return makeRenderMesh(surface, kSurfaceColor, crackColor);
  // Per surface vertex: the mean of its faces' cell-vertex values.
  std::vector<double> sum(surface.mesh.vertices.size(), 0.0), count(sum.size(), 0.0);
  for (size_t f = 0; f < surface.mesh.faces.size(); ++f) {
    const int v = surface.cellVertex[f];
    const double value = v >= 0 && v < static_cast<int>(values.size()) ? values[v] : 0.0;
    for (int c : surface.mesh.faces[f]) {
      sum[c] += value;
      count[c] += 1.0;
    }
  }
  const double scale = style.scaleMax > 0.0 ? 1.0 / style.scaleMax : 0.0;
  auto heat = [&](int v) { return heatColor(count[v] > 0.0 ? scale * sum[v] / count[v] : 0.0); };
  RenderMesh out;
  appendTag(out, surface, SurfaceTag::Outer, heat);
  if (style.tintCracks) {
    appendTag(out, surface, SurfaceTag::Crack, [](int) { return kCrackColor; });
  } else {
    appendTag(out, surface, SurfaceTag::Crack, heat);
  }
  return out;
}

}  // namespace galsculpt
