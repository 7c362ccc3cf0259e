#include "render_mesh.h"

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

RenderMesh makeRenderMesh(const VisualSurface& surface, const Vec3& outerColor,
                          const Vec3& crackColor) {
  RenderMesh out = makeRenderMesh(facesWithTag(surface, SurfaceTag::Outer), outerColor);
  const RenderMesh crack = makeRenderMesh(facesWithTag(surface, SurfaceTag::Crack), crackColor);
  const unsigned offset = static_cast<unsigned>(out.positions.size() / 3);
  out.positions.insert(out.positions.end(), crack.positions.begin(), crack.positions.end());
  out.normals.insert(out.normals.end(), crack.normals.begin(), crack.normals.end());
  out.colors.insert(out.colors.end(), crack.colors.begin(), crack.colors.end());
  for (unsigned i : crack.indices) out.indices.push_back(offset + i);
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
  RenderMesh out;
  for (SurfaceTag tag : {SurfaceTag::Outer, SurfaceTag::Crack}) {
    std::vector<int> source;
    const TriMesh part = facesWithTag(surface, tag, &source);
    RenderMesh r = makeRenderMesh(part, kSurfaceColor);
    for (size_t i = 0; i < source.size(); ++i) {
      const int v = source[i];
      const Vec3 c = tag == SurfaceTag::Crack && style.tintCracks
                         ? kCrackColor
                         : heatColor(count[v] > 0.0 ? scale * sum[v] / count[v] : 0.0);
      for (int k = 0; k < 3; ++k) r.colors[3 * i + k] = static_cast<float>(c[k]);
    }
    const unsigned offset = static_cast<unsigned>(out.positions.size() / 3);
    out.positions.insert(out.positions.end(), r.positions.begin(), r.positions.end());
    out.normals.insert(out.normals.end(), r.normals.begin(), r.normals.end());
    out.colors.insert(out.colors.end(), r.colors.begin(), r.colors.end());
    for (unsigned i : r.indices) out.indices.push_back(offset + i);
  }
  return out;
}

}  // namespace galsculpt
