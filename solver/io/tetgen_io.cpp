#include "solver/io/tetgen_io.h"

#include <algorithm>
#include <iomanip>

#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"
#include "solver/io/text_lines.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

// Counts read from headers are checked against what the file can hold before anything is
// reserved, so a header that claims 10^15 entries cannot exhaust memory.
void checkCount(const TextLines& lines, const TextLine& header, long long count, const char* what,
                long long maxReasonable) {
  if (count < 0) lines.fail(header.number, std::string("negative ") + what + " count");
  if (count > maxReasonable) {
    lines.fail(header.number, std::string(what) + " count " + std::to_string(count) +
                                  " exceeds the number of lines in the file");
  }
}

void expectTokens(const TextLines& lines, const TextLine& line, size_t expected,
                  const std::string& what) {
  if (line.tokens.size() != expected) {
    lines.fail(line.number, "expected " + std::to_string(expected) + " values for " + what +
                                ", got " + std::to_string(line.tokens.size()));
  }
}

void expectEnd(TextLines& lines, long long count, const char* what) {
  if (const TextLine* extra = lines.peek()) {
    lines.fail(extra->number, "unexpected data after the " + std::to_string(count) + " " + what +
                                  " announced in the header");
  }
}

int readNodes(const fs::path& path, TetMesh& mesh, std::string& stamp) {
  const std::string text = readWholeFile(path);
  stamp = findSetStamp(text);
  TextLines lines(path.string(), text);
  const TextLine& header = lines.next("the .node header '<points> 3 <attributes> <markers>'");
  if (header.tokens.size() < 1 || header.tokens.size() > 4) {
    lines.fail(header.number, "expected the .node header '<points> 3 <attributes> <markers>'");
  }
  const long long count = lines.parseInt(header, 0, "point count");
  const long long dim = header.tokens.size() > 1 ? lines.parseInt(header, 1, "dimension") : 3;
  const long long nAttr =
      header.tokens.size() > 2 ? lines.parseInt(header, 2, "attribute count") : 0;
  const long long nMark = header.tokens.size() > 3 ? lines.parseInt(header, 3, "marker flag") : 0;
  if (count == 0)
    lines.fail(header.number, "point count is 0 (points in a .poly file are not supported)");
  checkCount(lines, header, count, "point", lines.lastLineNumber());
  if (dim != 3) lines.fail(header.number, "dimension must be 3, got " + std::to_string(dim));
  if (nAttr < 0 || nAttr > 1000) lines.fail(header.number, "invalid attribute count");
  if (nMark != 0 && nMark != 1) lines.fail(header.number, "marker flag must be 0 or 1");
  const size_t perLine = 4 + static_cast<size_t>(nAttr + nMark);

  mesh.vertices.reserve(count);
  if (nMark) mesh.vertexMarkers.reserve(count);
  int base = 0;
  for (long long i = 0; i < count; ++i) {
    const TextLine& line =
        lines.next("point " + std::to_string(i + 1) + " of " + std::to_string(count));
    expectTokens(lines, line, perLine, "a point");
    const long long index = lines.parseInt(line, 0, "point number");
    if (i == 0) {
      if (index != 0 && index != 1) lines.fail(line.number, "first point must be numbered 0 or 1");
      base = static_cast<int>(index);
    } else if (index != base + i) {
      lines.fail(line.number, "point number " + std::to_string(index) +
                                  " out of sequence (expected " + std::to_string(base + i) + ")");
    }
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = lines.parseDouble(line, 1 + k, "coordinate");
    for (long long a = 0; a < nAttr; ++a) lines.parseDouble(line, 4 + a, "attribute");
    if (nMark)
      mesh.vertexMarkers.push_back(
          static_cast<int>(lines.parseInt(line, perLine - 1, "boundary marker")));
    mesh.vertices.push_back(p);
  }
  expectEnd(lines, count, "points");
  return base;
}

std::vector<int> readElements(const fs::path& path, int base, TetMesh& mesh, MeshReadReport& report,
                              std::string& stamp) {
  const std::string text = readWholeFile(path);
  stamp = findSetStamp(text);
  TextLines lines(path.string(), text);
  const TextLine& header = lines.next("the .ele header '<tets> <4|10> <attributes>'");
  if (header.tokens.size() < 1 || header.tokens.size() > 3) {
    lines.fail(header.number, "expected the .ele header '<tets> <4|10> <attributes>'");
  }
  const long long count = lines.parseInt(header, 0, "tet count");
  const long long perTet =
      header.tokens.size() > 1 ? lines.parseInt(header, 1, "nodes per tet") : 4;
  const long long nAttr =
      header.tokens.size() > 2 ? lines.parseInt(header, 2, "attribute count") : 0;
  checkCount(lines, header, count, "tet", lines.lastLineNumber());
  if (count == 0) lines.fail(header.number, "the mesh has no tets");
  if (perTet != 4 && perTet != 10) {
    lines.fail(header.number, "nodes per tet must be 4 or 10, got " + std::to_string(perTet));
  }
  if (nAttr < 0 || nAttr > 1000) lines.fail(header.number, "invalid attribute count");
  if (perTet == 10) report.notes.push_back(path.string() + ": 10-node tets, corners kept");
  const size_t perLine = 1 + static_cast<size_t>(perTet + nAttr);

  std::vector<int> tetLines;
  tetLines.reserve(count);
  mesh.tets.reserve(count);
  long long firstNumber = 0;
  for (long long i = 0; i < count; ++i) {
    const TextLine& line =
        lines.next("tet " + std::to_string(i + 1) + " of " + std::to_string(count));
    expectTokens(lines, line, perLine, "a tet");
    const long long number = lines.parseInt(line, 0, "tet number");
    if (i == 0) {
      if (number != 0 && number != 1) lines.fail(line.number, "first tet must be numbered 0 or 1");
      firstNumber = number;
    } else if (number != firstNumber + i) {
      lines.fail(line.number, "tet number " + std::to_string(number) +
                                  " out of sequence (expected " + std::to_string(firstNumber + i) +
                                  ")");
    }
    Tet t;
    for (int k = 0; k < 4; ++k) {
      const long long v = lines.parseInt(line, 1 + k, "vertex index") - base;
      if (v < 0 || v >= mesh.numVertices()) {
        lines.fail(line.number, "vertex index " + std::to_string(v + base) + " out of range [" +
                                    std::to_string(base) + ", " +
                                    std::to_string(mesh.numVertices() - 1 + base) + "]");
      }
      t[k] = static_cast<int>(v);
    }
    for (size_t k = 5; k < perLine; ++k) {
      if (k < static_cast<size_t>(1 + perTet)) {
        // A 10-node tet's mid-edge nodes are dropped, but they must still be vertices.
        const long long v = lines.parseInt(line, k, "vertex index") - base;
        if (v < 0 || v >= mesh.numVertices())
          lines.fail(line.number, "vertex index " + std::to_string(v + base) + " out of range [" +
                                      std::to_string(base) + ", " +
                                      std::to_string(mesh.numVertices() - 1 + base) + "]");
      } else {
        lines.parseDouble(line, k, "attribute");
      }
    }
    mesh.tets.push_back(t);
    tetLines.push_back(line.number);
  }
  expectEnd(lines, count, "tets");
  return tetLines;
}

void readFaces(const fs::path& path, int base, TetMesh& mesh, std::string& stamp) {
  const std::string text = readWholeFile(path);
  stamp = findSetStamp(text);
  TextLines lines(path.string(), text);
  const TextLine& header = lines.next("the .face header '<faces> <markers>'");
  if (header.tokens.size() < 1 || header.tokens.size() > 2) {
    lines.fail(header.number, "expected the .face header '<faces> <markers>'");
  }
  const long long count = lines.parseInt(header, 0, "face count");
  const long long nMark = header.tokens.size() > 1 ? lines.parseInt(header, 1, "marker flag") : 0;
  checkCount(lines, header, count, "face", lines.lastLineNumber());
  if (nMark != 0 && nMark != 1) lines.fail(header.number, "marker flag must be 0 or 1");
  for (long long i = 0; i < count; ++i) {
    const TextLine& line =
        lines.next("face " + std::to_string(i + 1) + " of " + std::to_string(count));
    // TetGen may append the two adjacent tets after the marker (-nn); accept them.
    if (line.tokens.size() != 4 + static_cast<size_t>(nMark) &&
        line.tokens.size() != 6 + static_cast<size_t>(nMark)) {
      expectTokens(lines, line, 4 + nMark, "a face");
    }
    lines.parseInt(line, 0, "face number");
    Tri f;
    for (int k = 0; k < 3; ++k) {
      const long long v = lines.parseInt(line, 1 + k, "vertex index") - base;
      if (v < 0 || v >= mesh.numVertices()) {
        lines.fail(line.number, "vertex index " + std::to_string(v + base) + " out of range");
      }
      f[k] = static_cast<int>(v);
    }
    mesh.faces.push_back(f);
    if (nMark)
      mesh.faceMarkers.push_back(static_cast<int>(lines.parseInt(line, 4, "boundary marker")));
  }
  expectEnd(lines, count, "faces");
}

}  // namespace

void checkSameSet(const fs::path& first, const std::string& firstStamp, const fs::path& other,
                  const std::string& otherStamp) {
  if (firstStamp == otherStamp) return;
  auto shown = [](const std::string& stamp) {
    return stamp.empty() ? std::string("none") : "'" + stamp + "'";
  };
  throw InputError(other.string(), 0,
                   "belongs to another write than " + first.filename().string() + " (set stamp " +
                       shown(otherStamp) + ", " + first.filename().string() + " has " +
                       shown(firstStamp) +
                       "): the set was not written whole, e.g. an export was killed; write it "
                       "again");
}

fs::path tetgenStem(const fs::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".node" || ext == ".ele" || ext == ".face") return fs::path(path).replace_extension();
  return path;
}

TetMesh readTetGen(const fs::path& path, MeshReadReport* reportOut) {
  const fs::path stem = tetgenStem(path);
  const fs::path nodePath = fs::path(stem).concat(".node");
  const fs::path elePath = fs::path(stem).concat(".ele");
  const fs::path facePath = fs::path(stem).concat(".face");
  requireRegularFile(nodePath);
  requireRegularFile(elePath);

  MeshReadReport report;
  TetMesh mesh;
  std::string eleStamp;
  report.indexBase = readNodes(nodePath, mesh, report.setStamp);
  const std::vector<int> tetLines = readElements(elePath, report.indexBase, mesh, report, eleStamp);
  checkSameSet(nodePath, report.setStamp, elePath, eleStamp);
  validateTets(mesh, elePath.string(), tetLines, report);
  std::error_code ec;
  if (fs::exists(facePath, ec)) {
    std::string faceStamp;
    readFaces(facePath, report.indexBase, mesh, faceStamp);
    checkSameSet(nodePath, report.setStamp, facePath, faceStamp);
  }
  if (reportOut) *reportOut = std::move(report);
  return mesh;
}

void addTetGen(FileSet& set, const fs::path& stem, const TetMesh& mesh,
               const std::vector<double>* tetAttribute) {
  const fs::path base = tetgenStem(stem);
  set.add(fs::path(base).concat(".node"), [&](std::ostream& out) {
    out << mesh.numVertices() << " 3 0 0\n" << std::setprecision(17);
    for (int i = 0; i < mesh.numVertices(); ++i) {
      const Vec3& p = mesh.vertices[i];
      out << i << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    }
    out << "# written by galsculpt\n" << set.stampLine();
  });
  set.add(fs::path(base).concat(".ele"), [&](std::ostream& out) {
    const bool attr = tetAttribute && tetAttribute->size() == mesh.tets.size();
    out << mesh.numTets() << " 4 " << (attr ? 1 : 0) << '\n' << std::setprecision(17);
    for (int i = 0; i < mesh.numTets(); ++i) {
      const Tet& t = mesh.tets[i];
      out << i << ' ' << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3];
      if (attr) out << ' ' << (*tetAttribute)[i];
      out << '\n';
    }
    out << "# written by galsculpt\n" << set.stampLine();
  });
  const std::vector<Tri> faces = boundaryFaces(mesh);
  set.add(fs::path(base).concat(".face"), [&](std::ostream& out) {
    out << faces.size() << " 1\n";
    for (size_t i = 0; i < faces.size(); ++i) {
      out << i << ' ' << faces[i][0] << ' ' << faces[i][1] << ' ' << faces[i][2] << " 1\n";
    }
    out << "# written by galsculpt\n" << set.stampLine();
  });
}

void writeTetGen(const fs::path& stem, const TetMesh& mesh,
                 const std::vector<double>* tetAttribute) {
  FileSet set;
  addTetGen(set, stem, mesh, tetAttribute);
  // A .damage beside belongs to the mesh it was written with, not to this one.
  set.remove(fs::path(tetgenStem(stem)).concat(".damage"));
  set.commit();
}

}  // namespace galsculpt
