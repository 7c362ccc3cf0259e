#include "solver/io/gmsh_io.h"

#include <iomanip>
#include <unordered_map>

#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"
#include "solver/io/text_lines.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

constexpr int kTet4 = 4;
constexpr int kTet10 = 11;

int nodesOfElementType(int type) {
  // Linear and common quadratic types, enough to skip blocks we do not read.
  switch (type) {
    case 1:
      return 2;  // line
    case 2:
      return 3;  // triangle
    case 3:
      return 4;  // quad
    case 4:
      return 4;  // tet
    case 5:
      return 8;  // hex
    case 6:
      return 6;  // prism
    case 7:
      return 5;  // pyramid
    case 8:
      return 3;  // line3
    case 9:
      return 6;  // triangle6
    case 11:
      return 10;  // tet10
    case 15:
      return 1;  // point
    default:
      return -1;
  }
}

void expectSectionEnd(TextLines& lines, const std::string& name) {
  const TextLine& end = lines.next("$End" + name);
  if (end.tokens.size() != 1 || end.tokens[0] != "$End" + name) {
    lines.fail(end.number, "expected $End" + name);
  }
}

// The sections' readers share the file's lines, the mesh being built and the tags seen.
struct GmshReader {
  TextLines& lines;
  TetMesh& mesh;
  MeshReadReport& report;
  std::unordered_map<long long, int> nodeIndex;  // node tag -> vertex
  std::vector<int> tetLines;                     // line of each tet, for validation messages
  long long maxCount = 0;                        // no count may exceed the file's line count

  void readFormat() {
    const TextLine& f = lines.next("the format line '4.1 0 8'");
    if (f.tokens.size() != 3) lines.fail(f.number, "expected the format line '4.1 0 8'");
    if (f.tokens[0] != "4.1") {
      lines.fail(f.number, "unsupported MSH version " + std::string(f.tokens[0]) + " (need 4.1)");
    }
    if (lines.parseInt(f, 1, "file type") != 0)
      lines.fail(f.number, "binary MSH is not supported; save as ASCII");
    expectSectionEnd(lines, "MeshFormat");
  }

  void readNodes() {
    const TextLine& h = lines.next("the $Nodes header");
    if (h.tokens.size() != 4) lines.fail(h.number, "expected '<blocks> <nodes> <minTag> <maxTag>'");
    const long long blocks = lines.parseInt(h, 0, "block count");
    const long long total = lines.parseInt(h, 1, "node count");
    if (blocks < 0 || blocks > maxCount || total < 0 || total > maxCount) {
      lines.fail(h.number, "node counts exceed the size of the file");
    }
    mesh.vertices.reserve(total);
    for (long long b = 0; b < blocks; ++b) readNodeBlock();
    if (static_cast<long long>(mesh.vertices.size()) != total) {
      lines.fail(h.number, "header announces " + std::to_string(total) + " nodes, blocks hold " +
                               std::to_string(mesh.vertices.size()));
    }
    expectSectionEnd(lines, "Nodes");
  }

  void readNodeBlock() {
    const TextLine& bh = lines.next("a node block header");
    if (bh.tokens.size() != 4) lines.fail(bh.number, "expected '<dim> <tag> <parametric> <count>'");
    const long long parametric = lines.parseInt(bh, 2, "parametric flag");
    const long long n = lines.parseInt(bh, 3, "node count");
    if (parametric != 0) lines.fail(bh.number, "parametric nodes are not supported");
    if (n < 0 || n > maxCount) lines.fail(bh.number, "node count exceeds the size of the file");
    std::vector<long long> tags(n);
    for (long long i = 0; i < n; ++i) {
      const TextLine& t = lines.next("a node tag");
      if (t.tokens.size() != 1) lines.fail(t.number, "expected one node tag");
      tags[i] = lines.parseInt(t, 0, "node tag");
    }
    for (long long i = 0; i < n; ++i) {
      const TextLine& c = lines.next("node coordinates");
      if (c.tokens.size() != 3) lines.fail(c.number, "expected 3 coordinates");
      Vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = lines.parseDouble(c, k, "coordinate");
      if (!nodeIndex.emplace(tags[i], mesh.numVertices()).second) {
        lines.fail(c.number, "duplicate node tag " + std::to_string(tags[i]));
      }
      mesh.vertices.push_back(p);
    }
  }

  void readElements(const fs::path& path) {
    const TextLine& h = lines.next("the $Elements header");
    if (h.tokens.size() != 4)
      lines.fail(h.number, "expected '<blocks> <elements> <minTag> <maxTag>'");
    const long long blocks = lines.parseInt(h, 0, "block count");
    if (blocks < 0 || blocks > maxCount)
      lines.fail(h.number, "block count exceeds the size of the file");
    for (long long b = 0; b < blocks; ++b) readElementBlock(path);
    expectSectionEnd(lines, "Elements");
  }

  // Tets (4 and 10 nodes, corners kept) are read; other element types are checked and skipped.
  void readElementBlock(const fs::path& path) {
    const TextLine& bh = lines.next("an element block header");
    if (bh.tokens.size() != 4) lines.fail(bh.number, "expected '<dim> <tag> <type> <count>'");
    const int type = static_cast<int>(lines.parseInt(bh, 2, "element type"));
    const long long n = lines.parseInt(bh, 3, "element count");
    if (n < 0 || n > maxCount) lines.fail(bh.number, "element count exceeds the size of the file");
    const int perElement = nodesOfElementType(type);
    if (perElement < 0) lines.fail(bh.number, "unsupported element type " + std::to_string(type));
    if (type == kTet10) report.notes.push_back(path.string() + ": 10-node tets, corners kept");
    for (long long i = 0; i < n; ++i) {
      const TextLine& e = lines.next("an element");
      if (e.tokens.size() != static_cast<size_t>(1 + perElement)) {
        lines.fail(e.number, "expected " + std::to_string(1 + perElement) +
                                 " values for an element of type " + std::to_string(type) +
                                 ", got " + std::to_string(e.tokens.size()));
      }
      if (type != kTet4 && type != kTet10) continue;
      Tet t;
      for (int k = 0; k < 4; ++k) {
        const long long nodeTag = lines.parseInt(e, 1 + k, "node tag");
        const auto it = nodeIndex.find(nodeTag);
        if (it == nodeIndex.end())
          lines.fail(e.number, "unknown node tag " + std::to_string(nodeTag));
        t[k] = it->second;
      }
      mesh.tets.push_back(t);
      tetLines.push_back(e.number);
    }
  }

  // Skips an unknown section ($Entities, $PhysicalNames, ...).
  void skipSection(std::string_view tag) {
    const std::string endTag = "$End" + std::string(tag.substr(1));
    while (true) {
      const TextLine& s = lines.next(endTag);
      if (s.tokens.size() == 1 && s.tokens[0] == endTag) break;
    }
  }
};

}  // namespace

TetMesh readGmsh(const fs::path& path, MeshReadReport* reportOut) {
  const std::string text = readWholeFile(path);
  TextLines lines(path.string(), text, 0);
  MeshReadReport report;
  TetMesh mesh;
  GmshReader reader{lines, mesh, report, {}, {}, lines.lastLineNumber()};
  bool sawFormat = false, sawNodes = false, sawElements = false;
  while (!lines.atEnd()) {
    const TextLine& line = lines.next("a section");
    const std::string_view tag = line.tokens[0];
    if (tag == "$MeshFormat") {
      reader.readFormat();
      sawFormat = true;
    } else if (tag == "$Nodes") {
      if (!sawFormat) lines.fail(line.number, "$Nodes before $MeshFormat");
      reader.readNodes();
      sawNodes = true;
    } else if (tag == "$Elements") {
      if (!sawNodes) lines.fail(line.number, "$Elements before $Nodes");
      reader.readElements(path);
      sawElements = true;
    } else if (tag.size() > 1 && tag[0] == '$' && tag.substr(0, 4) != "$End") {
      reader.skipSection(tag);
    } else {
      lines.fail(line.number, "expected a section such as $MeshFormat, got '" +
                                  std::string(tag.substr(0, 40)) + "'");
    }
  }
  if (!sawFormat) throw InputError(path.string(), 0, "not a Gmsh file: no $MeshFormat section");
  if (!sawElements || mesh.tets.empty())
    throw InputError(path.string(), 0, "no tetrahedra in the file");
  validateTets(mesh, path.string(), reader.tetLines, report);
  if (reportOut) *reportOut = std::move(report);
  return mesh;
}

void writeGmsh(const fs::path& path, const TetMesh& mesh) {
  writeFileAtomically(path, [&](std::ostream& out) {
    const BoundingBox box = boundingBox(mesh.vertices);
    out << std::setprecision(17);
    out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
    out << "$Entities\n0 0 0 1\n1 " << box.min.x() << ' ' << box.min.y() << ' ' << box.min.z()
        << ' ' << box.max.x() << ' ' << box.max.y() << ' ' << box.max.z() << " 0 0\n$EndEntities\n";
    const int n = mesh.numVertices();
    out << "$Nodes\n1 " << n << " 1 " << n << "\n3 1 0 " << n << '\n';
    for (int i = 0; i < n; ++i) out << i + 1 << '\n';
    for (const Vec3& p : mesh.vertices) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    out << "$EndNodes\n";
    const int m = mesh.numTets();
    out << "$Elements\n1 " << m << " 1 " << m << "\n3 1 4 " << m << '\n';
    for (int i = 0; i < m; ++i) {
      const Tet& t = mesh.tets[i];
      out << i + 1 << ' ' << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << ' ' << t[3] + 1
          << '\n';
    }
    out << "$EndElements\n";
  });
}

}  // namespace galsculpt
