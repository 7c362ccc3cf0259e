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

}  // namespace galsculpt
