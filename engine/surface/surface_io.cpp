#include "engine/surface/surface_io.h"

#include <stdlib.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <algorithm>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <map>
#include <memory>
#include <mutex>

#include "engine/meshing/off_ply_reader.h"
#include "engine/scene/json_reader.h"
#include "engine/surface/checked_export_io.h"
#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

const char* exportFormatFor(const std::string& ext) {
  if (ext == ".obj") return "objnomtl";
  if (ext == ".ply") return "plyb";
  if (ext == ".stl") return "stlb";
  if (ext == ".gltf") return "gltf2";
  if (ext == ".glb") return "glb2";
  return nullptr;
}

// assimp's scene, checked as it is walked: it hands over indices as the file wrote them.
void appendNode(const std::string& file, const aiScene* scene, const aiNode* node,
                const aiMatrix4x4& parent, std::vector<Vec3>& positions, std::vector<Tri>& faces,
                int depth) {
  if (depth > 256) throw InputError(file, 0, "the scene's node tree nests deeper than 256 levels");
  const aiMatrix4x4 transform = parent * node->mTransformation;
  for (unsigned m = 0; m < node->mNumMeshes; ++m) {
    if (node->mMeshes[m] >= scene->mNumMeshes || !scene->mMeshes[node->mMeshes[m]])
      throw InputError(file, 0,
                       "a node names mesh " + std::to_string(node->mMeshes[m]) + " (the file has " +
                           std::to_string(scene->mNumMeshes) + ")");
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
    const int offset = static_cast<int>(positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = transform * mesh->mVertices[v];
      positions.push_back(Vec3(p.x, p.y, p.z));
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines are not part of a surface
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices)
          throw InputError(file, 0,
                           "face " + std::to_string(f) + " of mesh " +
                               std::to_string(node->mMeshes[m]) + " names vertex " +
                               std::to_string(face.mIndices[k]) + " (the mesh has " +
                               std::to_string(mesh->mNumVertices) + ")");
      }
      faces.push_back({offset + static_cast<int>(face.mIndices[0]),
                       offset + static_cast<int>(face.mIndices[1]),
                       offset + static_cast<int>(face.mIndices[2])});
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) {
    appendNode(file, scene, node->mChildren[c], transform, positions, faces, depth + 1);
  }
}

// assimp's warnings during one import. Some of its readers drop what is malformed with a
// warning only (glTF 2 skips a face whose index is out of range): those warnings are errors
// here. assimp's logger is process-wide, hence one import at a time.
class ImportWarnings : public Assimp::LogStream {
 public:
  ImportWarnings() {
    Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);
    Assimp::DefaultLogger::get()->attachStream(this, Assimp::Logger::Warn | Assimp::Logger::Err);
  }
  ~ImportWarnings() override {
    Assimp::DefaultLogger::get()->detachStream(this, Assimp::Logger::Warn | Assimp::Logger::Err);
    Assimp::DefaultLogger::kill();
  }
  ImportWarnings(const ImportWarnings&) = delete;
  ImportWarnings& operator=(const ImportWarnings&) = delete;
  void write(const char* message) override { messages.emplace_back(message); }
  std::vector<std::string> messages;
};

std::mutex& importMutex() {
  static std::mutex m;
  return m;
}

// The messages that mean the file's geometry was dropped or altered, not merely unusual: every
// error assimp logs while still returning a scene (an STL facet of four corners), and the
// warnings that say data was dropped. Materials and textures are not read here, so what assimp
// says of them (an unknown texture type in an .mtl) is no reason to refuse a mesh.
const std::string* droppedData(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) {
    std::string lower = w;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    bool appearance = false;
    for (const char* word : {"mtl", "material", "texture"})
      appearance = appearance || lower.find(word) != std::string::npos;
    if (appearance) continue;
    if (w.rfind("Error", 0) == 0) return &w;
    for (const char* sign : {"out of range", "out-of-range", "dropped", "invalid", "overflow"}) {
      if (lower.find(sign) != std::string::npos) return &w;
    }
  }
  return nullptr;
}

// glTF's JSON, checked for nesting before assimp's recursive parser sees it (a deeply nested
// file overflowed the stack).
void checkJsonDepth(const std::string& name, std::string_view json, size_t offset) {
  if (const size_t at = jsonTooDeepAt(json); at != std::string::npos)
    throw InputError(name + ": byte " + std::to_string(offset + at) + ": JSON nests deeper than " +
                     std::to_string(kMaxJsonDepth) + " levels");
}

// A .gltf's JSON: not too deep for assimp's parser, and buffers and images only in its own
// folder or below (a uri such as ../../../../etc/passwd was read as vertex data).
void checkGltfJson(const fs::path& path) {
  const std::string text = readWholeFile(path);
  checkJsonDepth(path.string(), text, 0);
  const nlohmann::json j = parseJsonText(text, path.string());
  for (const char* list : {"buffers", "images"}) {
    if (!j.is_object() || !j.contains(list) || !j[list].is_array()) continue;
    for (size_t i = 0; i < j[list].size(); ++i) {
      const nlohmann::json& item = j[list][i];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      const fs::path p = fs::path(uri).lexically_normal();
      if (p.is_absolute() || uri.find("://") != std::string::npos ||
          (!p.empty() && *p.begin() == ".."))
        throw InputError(path.string(), 0,
                         "$." + std::string(list) + "[" + std::to_string(i) + "].uri: '" + uri +
                             "' lies outside the glTF's folder");
    }
  }
}

// GLB's own header, checked before assimp reads it: assimp trusts the length fields.
void checkGlbHeader(const fs::path& path) {
  const std::string data = readWholeFile(path);
  auto u32 = [&](size_t at) {
    std::uint32_t v = 0;
    std::memcpy(&v, data.data() + at, 4);
    return v;
  };
  const std::string name = path.string();
  if (data.size() < 12)
    throw InputError(name + ": byte " + std::to_string(data.size()) +
                     ": truncated (a GLB header is 12 bytes)");
  if (data.compare(0, 4, "glTF") != 0)
    throw InputError(name + ": byte 0: not a GLB file (it must start with 'glTF')");
  if (u32(4) != 2)
    throw InputError(name + ": byte 4: GLB version " + std::to_string(u32(4)) +
                     " (only version 2 is read)");
  if (u32(8) != data.size())
    throw InputError(name + ": byte 8: the header's length " + std::to_string(u32(8)) +
                     " is not the file's size " + std::to_string(data.size()));
  for (size_t at = 12; at < data.size();) {
    if (data.size() - at < 8)
      throw InputError(name + ": byte " + std::to_string(at) + ": truncated chunk header");
    const std::uint32_t length = u32(at);
    if (length > data.size() - at - 8)
      throw InputError(name + ": byte " + std::to_string(at) + ": a chunk of " +
                       std::to_string(length) + " bytes runs past the end of the file");
    if (at == 12) checkJsonDepth(name, std::string_view(data).substr(at + 8, length), at + 8);
    at += 8 + length;
  }
}

}  // namespace

bool isSurfaceFile(const fs::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".off" || ext == ".gltf" ||
         ext == ".glb";
}

TriMesh readSurface(const fs::path& path) {
  requireRegularFile(path);
  std::vector<Vec3> positions;
  std::vector<Tri> faces;
  const std::string ext = lowerExtension(path);
  if (ext == ".off" || ext == ".ply") {
    // Our strict readers (off_ply_reader.h: assimp clamps or misreads what is malformed).
    RawSurface raw = ext == ".off" ? readOff(path) : readPly(path);
    positions = std::move(raw.vertices);
    faces = std::move(raw.faces);
  } else {
    if (ext == ".glb") checkGlbHeader(path);
    if (ext == ".gltf") checkGltfJson(path);
    const std::lock_guard<std::mutex> lock(importMutex());
    ImportWarnings warnings;
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(
        path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                           aiProcess_SortByPType | aiProcess_ValidateDataStructure);
    if (!scene || !scene->mRootNode) {
      throw InputError(path.string(), 0,
                       std::string("cannot read surface: ") + importer.GetErrorString());
    }
    if (const std::string* w = droppedData(warnings.messages)) {
      std::string message = *w;
      if (const size_t colon = message.find(": "); colon != std::string::npos && colon < 16)
        message = message.substr(colon + 2);  // "Warn,  T0: " prefix
      while (!message.empty() && (message.back() == '\n' || message.back() == '\r'))
        message.pop_back();
      throw InputError(path.string(), 0, "malformed data (assimp: " + message + ")");
    }
    appendNode(path.string(), scene, scene->mRootNode, aiMatrix4x4(), positions, faces, 0);
  }
  if (faces.empty()) throw InputError(path.string(), 0, "the file holds no triangles");
  for (const Vec3& p : positions) {
    if (!p.allFinite()) throw InputError(path.string(), 0, "non-finite vertex coordinate");
  }

  // Weld vertices at exactly the same position (across meshes, and for STL corners).
  TriMesh out;
  std::map<std::array<double, 3>, int> index;
  std::vector<int> remap(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const std::array<double, 3> key{positions[i].x(), positions[i].y(), positions[i].z()};
    const auto [it, inserted] = index.emplace(key, out.numVertices());
    if (inserted) out.vertices.push_back(positions[i]);
    remap[i] = it->second;
  }
  out.faces.reserve(faces.size());
  for (Tri f : faces) {
    for (int& v : f) v = remap[v];
    out.faces.push_back(f);
  }
  return out;
}

namespace {

// One mesh of an exported scene: its own vertices (and normals, optional) and faces.
struct ExportPart {
  std::string name;
  const TriMesh* mesh;
  const std::vector<Vec3>* normals;
};

aiVector3D toAi(const Vec3& p) {
  return aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()),
                    static_cast<ai_real>(p.z()));
}

fs::path checkedOutputDir(const fs::path& path) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw OutputError("cannot write " + path.string() + ": directory " + dir.string() +
                      " does not exist");
  }
  return dir;
}

void exportWithAssimp(const fs::path& path, const char* format,
                      const std::vector<ExportPart>& parts) {
  const fs::path dir = checkedOutputDir(path);
  // The aiScene owns and frees everything attached below.
  auto scene = std::make_unique<aiScene>();
  const unsigned n = static_cast<unsigned>(parts.size());
  scene->mRootNode = new aiNode();
  scene->mMaterials = new aiMaterial*[n];
  scene->mMeshes = new aiMesh*[n];
  scene->mNumMaterials = scene->mNumMeshes = n;
  scene->mRootNode->mMeshes = new unsigned[n];
  scene->mRootNode->mNumMeshes = n;
  for (unsigned m = 0; m < n; ++m) {
    const TriMesh& mesh = *parts[m].mesh;
    auto* material = new aiMaterial();
    const aiString name(parts[m].name);
    material->AddProperty(&name, AI_MATKEY_NAME);
    scene->mMaterials[m] = material;
    auto* out = new aiMesh();
    scene->mMeshes[m] = out;
    scene->mRootNode->mMeshes[m] = m;
    out->mName = aiString(parts[m].name);
    out->mMaterialIndex = m;
    out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    out->mNumVertices = static_cast<unsigned>(mesh.vertices.size());
    out->mVertices = new aiVector3D[out->mNumVertices];
    for (unsigned i = 0; i < out->mNumVertices; ++i) out->mVertices[i] = toAi(mesh.vertices[i]);
    const std::vector<Vec3>* normals = parts[m].normals;
    if (normals && normals->size() == mesh.vertices.size()) {
      out->mNormals = new aiVector3D[out->mNumVertices];
      for (unsigned i = 0; i < out->mNumVertices; ++i) out->mNormals[i] = toAi((*normals)[i]);
    }
    out->mNumFaces = static_cast<unsigned>(mesh.faces.size());
    out->mFaces = new aiFace[out->mNumFaces];
    for (unsigned f = 0; f < out->mNumFaces; ++f) {
      out->mFaces[f].mNumIndices = 3;
      out->mFaces[f].mIndices = new unsigned[3];
      for (int k = 0; k < 3; ++k)
        out->mFaces[f].mIndices[k] = static_cast<unsigned>(mesh.faces[f][k]);
    }
  }

  // Export into a private folder beside the target (same file system), then rename every file
  // it produced (glTF writes a .bin next to the .gltf) into place.
  std::string pattern = (dir / ".galsculpt-export-XXXXXX").string();
  if (!mkdtemp(pattern.data())) {
    throw OutputError("cannot write " + path.string() + ": cannot create a temporary folder in " +
                      dir.string());
  }
  const fs::path tmpDir = pattern;
  std::error_code ec;
  Assimp::Exporter exporter;
  auto* io = new CheckedExportIO;  // the exporter owns and deletes it
  exporter.SetIOHandler(io);
  const aiReturn status = exporter.Export(scene.get(), format, (tmpDir / path.filename()).string());
  if (status != aiReturn_SUCCESS || !io->failure().empty()) {
    // The system's error (a full disk) over assimp's summary of it.
    const std::string reason = io->failure().empty() ? exporter.GetErrorString() : io->failure();
    fs::remove_all(tmpDir, ec);
    throw OutputError("cannot write " + path.string() + ": " + reason);
  }
  for (const auto& entry : fs::directory_iterator(tmpDir)) {
    fs::rename(entry.path(), dir / entry.path().filename(), ec);
    if (ec) {
      const std::string reason = ec.message();
      fs::remove_all(tmpDir, ec);
      throw OutputError("cannot write " + path.string() + ": " + reason);
    }
  }
  fs::remove_all(tmpDir, ec);
}

const char* checkedFormat(const fs::path& path) {
  const char* format = exportFormatFor(lowerExtension(path));
  if (!format) {
    throw OutputError("cannot write " + path.string() + ": unknown surface format '" +
                      lowerExtension(path) + "' (use .obj, .ply, .stl, .gltf or .glb)");
  }
  return format;
}

// OBJ by hand: assimp's OBJ exporter merges vertices that share a position, which would weld
// the two sides of a crack that has not opened yet. One vertex list for the whole surface, so
// outer and crack faces stay connected; outer faces take smooth per-vertex normals, crack faces
// one normal each (flat, as the app shades them), so crack edges stay sharp.
void writeObj(const fs::path& path, const VisualSurface& s) {
  checkedOutputDir(path);
  const std::vector<Vec3> outerNormals = outerShadingNormals(s);
  const int n = s.mesh.numVertices();
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "# galsculpt visualization surface: " << n << " vertices, " << s.mesh.numFaces()
        << " faces; groups 'outer' (the body's surface) and 'crack' (crack faces)\n";
    out << std::setprecision(9);
    auto vector = [&](const char* kind, const Vec3& p) {
      out << kind << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    };
    for (const Vec3& p : s.mesh.vertices) vector("v", p);
    for (const Vec3& p : outerNormals) vector("vn", p);
    for (size_t f = 0; f < s.mesh.faces.size(); ++f) {
      if (s.tags[f] != SurfaceTag::Crack) continue;
      const Tri& t = s.mesh.faces[f];
      const std::vector<Vec3>& x = s.mesh.vertices;
      vector("vn", (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).stableNormalized());
    }
    for (SurfaceTag tag : {SurfaceTag::Outer, SurfaceTag::Crack}) {
      bool header = false;
      int crackNormal = n;  // crack faces' normals follow the per-vertex ones, in face order
      for (size_t f = 0; f < s.mesh.faces.size(); ++f) {
        if (s.tags[f] != tag) continue;
        if (!header) out << (tag == SurfaceTag::Crack ? "g crack\n" : "g outer\n");
        header = true;
        out << 'f';
        const int flat = ++crackNormal;
        for (int v : s.mesh.faces[f])
          out << ' ' << v + 1 << "//" << (tag == SurfaceTag::Crack ? flat : v + 1);
        out << '\n';
      }
    }
  });
}

}  // namespace

void writeSurface(const fs::path& path, const TriMesh& mesh, const std::vector<Vec3>* normals) {
  exportWithAssimp(path, checkedFormat(path), {{"surface", &mesh, normals}});
}

void writeVisualSurface(const fs::path& path, const VisualSurface& surface) {
  const char* format = checkedFormat(path);
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") {
    writeObj(path, surface);
  } else if (ext == ".gltf" || ext == ".glb") {
    // One mesh per tag (materials 'outer' and 'crack'), each with its own normals.
    std::vector<TriMesh> parts;
    std::vector<std::vector<Vec3>> normals;
    std::vector<ExportPart> list;
    for (SurfaceTag tag : {SurfaceTag::Outer, SurfaceTag::Crack}) {
      parts.push_back(facesWithTag(surface, tag));
      normals.push_back(vertexNormals(parts.back()));
    }
    for (int k = 0; k < 2; ++k) {
      if (parts[k].faces.empty()) continue;
      list.push_back({k == 0 ? "outer" : "crack", &parts[k], &normals[k]});
    }
    exportWithAssimp(path, format, list);
  } else {
    // PLY and STL hold one untagged triangle list.
    exportWithAssimp(path, format, {{"surface", &surface.mesh, nullptr}});
  }
}

}  // namespace galsculpt
