#include "engine/meshing/off_ply_reader.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>

#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"
#include "solver/io/text_lines.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

// Appends the fan of a polygon; `corner` holds its indices, already checked.
void addFan(const std::vector<int>& corner, std::vector<Tri>& faces) {
  for (size_t k = 1; k + 1 < corner.size(); ++k)
    faces.push_back({corner[0], corner[k], corner[k + 1]});
}

}  // namespace

RawSurface readOff(const fs::path& path) {
  const std::string text = readWholeFile(path);
  TextLines lines(path.string(), text);
  const TextLine& header = lines.next("the OFF header");
  const std::string_view magic = header.tokens[0];
  if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF" ||
      magic.find_first_not_of("STCN") != magic.size() - 3)
    lines.fail(header.number, "not an OFF file (it must start with 'OFF')");
  // Counts follow on the header line or on the next line.
  const TextLine* countLine = &header;
  size_t first = 1;
  if (header.tokens.size() == 1) {
    countLine = &lines.next("the vertex and face counts");
    first = 0;
  }
  if (countLine->tokens.size() < first + 2 || countLine->tokens.size() > first + 3)
    lines.fail(countLine->number, "expected the vertex, face and edge counts");
  const long long nv = lines.parseInt(*countLine, first, "the vertex count");
  const long long nf = lines.parseInt(*countLine, first + 1, "the face count");
  if (nv < 0 || nf < 0) lines.fail(countLine->number, "negative count");
  // Every vertex and face takes a line: counts beyond the file are refused before allocating.
  if (static_cast<unsigned long long>(nv) + static_cast<unsigned long long>(nf) > lines.remaining())
    lines.fail(countLine->number, "the header promises " + std::to_string(nv) + " vertices and " +
                                      std::to_string(nf) + " faces, the file has " +
                                      std::to_string(lines.remaining()) + " more lines");
  RawSurface s;
  s.vertices.reserve(static_cast<size_t>(nv));
  for (long long v = 0; v < nv; ++v) {
    const TextLine& line =
        lines.next("vertex " + std::to_string(v + 1) + " of " + std::to_string(nv));
    if (line.tokens.size() < 3) lines.fail(line.number, "expected x y z");
    s.vertices.push_back(Vec3(lines.parseDouble(line, 0, "coordinate"),
                              lines.parseDouble(line, 1, "coordinate"),
                              lines.parseDouble(line, 2, "coordinate")));
  }
  std::vector<int> corner;
  for (long long f = 0; f < nf; ++f) {
    const TextLine& line =
        lines.next("face " + std::to_string(f + 1) + " of " + std::to_string(nf));
    const long long n = lines.parseInt(line, 0, "the number of corners");
    if (n < 3) lines.fail(line.number, "a face needs at least 3 corners, got " + std::to_string(n));
    if (static_cast<unsigned long long>(n) + 1 > line.tokens.size())
      lines.fail(line.number, "the face has " + std::to_string(n) + " corners but the line lists " +
                                  std::to_string(line.tokens.size() - 1) + " values");
    corner.clear();
    for (long long k = 0; k < n; ++k) {
      const long long i = lines.parseInt(line, static_cast<size_t>(k + 1), "a vertex index");
      if (i < 0 || i >= nv)
        lines.fail(line.number, "vertex index " + std::to_string(i) + " out of range [0, " +
                                    std::to_string(nv - 1) + "]");
      corner.push_back(static_cast<int>(i));
    }
    addFan(corner, s.faces);
  }
  if (!lines.atEnd())
    lines.fail(lines.peek()->number, "unexpected data after the " + std::to_string(nf) + " faces");
  return s;
}

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool plyType(std::string_view name, PlyType& type) {
  static const std::pair<const char*, PlyType> kNames[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [n, t] : kNames) {
    if (name == n) {
      type = t;
      return true;
    }
  }
  return false;
}

size_t plySize(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

struct PlyProperty {
  std::string name;
  bool list = false;
  PlyType countType = PlyType::UInt8;
  PlyType type = PlyType::Float32;
};

struct PlyElement {
  std::string name;
  unsigned long long count = 0;
  std::vector<PlyProperty> properties;
  int headerLine = 0;
};

// Binary body: bounds-checked reads with the byte offset in every error.
class PlyBinary {
 public:
  PlyBinary(const std::string& data, size_t offset, bool bigEndian, std::string file)
      : data_(data),
        offset_(offset),
        swap_(bigEndian != (std::endian::native == std::endian::big)),
        file_(std::move(file)) {}
  double read(PlyType t, const char* what) {
    const size_t n = plySize(t);
    if (data_.size() - offset_ < n)
      throw InputError(file_ + ": truncated at byte " + std::to_string(data_.size()) + ": " + what +
                       " needs " + std::to_string(n) + " bytes from byte " +
                       std::to_string(offset_));
    unsigned char b[8];
    std::memcpy(b, data_.data() + offset_, n);
    if (swap_) {
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    }
    offset_ += n;
    switch (t) {
      case PlyType::Int8:
        return static_cast<double>(static_cast<std::int8_t>(b[0]));
      case PlyType::UInt8:
        return b[0];
      case PlyType::Int16:
        return load<std::int16_t>(b);
      case PlyType::UInt16:
        return load<std::uint16_t>(b);
      case PlyType::Int32:
        return load<std::int32_t>(b);
      case PlyType::UInt32:
        return load<std::uint32_t>(b);
      case PlyType::Float32:
        return load<float>(b);
      case PlyType::Float64:
        return load<double>(b);
    }
    return 0.0;
  }
  size_t offset() const { return offset_; }
  size_t remaining() const { return data_.size() - offset_; }
  [[noreturn]] void fail(size_t at, const std::string& message) const {
    throw InputError(file_ + ": byte " + std::to_string(at) + ": " + message);
  }

 private:
  template <typename T>
  static double load(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return static_cast<double>(v);
  }
  const std::string& data_;
  size_t offset_;
  bool swap_;
  std::string file_;
};

int checkedIndex(double value, long long nv, const std::function<void(const std::string&)>& fail) {
  if (!(value == std::floor(value)) || value < 0 || value >= static_cast<double>(nv)) {
    std::string shown = std::isfinite(value) && value == std::floor(value)
                            ? std::to_string(static_cast<long long>(value))
                            : std::to_string(value);
    fail("vertex index " + shown + " out of range [0, " + std::to_string(nv - 1) + "]");
  }
  return static_cast<int>(value);
}

// A PLY file's header: its elements, which of them hold the vertices and faces, and how much
// data the body must hold at least.
struct PlyHeader {
  std::string name;  // the file, for messages
  bool ascii = true, bigEndian = false;
  size_t bodyStart = 0;  // the first byte after the end_header line
  int endHeaderLine = 0;
  std::vector<PlyElement> elements;
  const PlyElement* vertexElement = nullptr;
  const PlyElement* faceElement = nullptr;
  int xyz[3] = {-1, -1, -1};      // the vertex element's x, y, z properties
  int indexProperty = -1;         // the face element's vertex_indices
  unsigned long long needed = 0;  // lines (ascii) or bytes (binary) the records take at least

  long long vertexCount() const { return static_cast<long long>(vertexElement->count); }

  PlyHeader() = default;
  PlyHeader(const PlyHeader&) = delete;  // it points into its own elements
  PlyHeader(PlyHeader&&) = default;      // a vector's move keeps them where they are
};

// One 'property' line of the header, added to the last element.
PlyProperty readPlyProperty(TextLines& header, const TextLine& line) {
  PlyProperty p;
  const bool list = line.tokens.size() >= 2 && line.tokens[1] == "list";
  if ((list && line.tokens.size() != 5) || (!list && line.tokens.size() != 3))
    header.fail(line.number, "expected 'property TYPE NAME' or 'property list COUNT TYPE NAME'");
  p.list = list;
  if (list && !plyType(line.tokens[2], p.countType))
    header.fail(line.number, "unknown type '" + std::string(line.tokens[2]) + "'");
  if (list && (p.countType == PlyType::Float32 || p.countType == PlyType::Float64))
    header.fail(line.number, "a list's count must be an integer type");
  if (!plyType(line.tokens[list ? 3 : 1], p.type))
    header.fail(line.number, "unknown type '" + std::string(line.tokens[list ? 3 : 1]) + "'");
  p.name = std::string(line.tokens.back());
  return p;
}

// The vertex element's x, y, z and the face element's index list, which a surface needs.
void findPlySurfaceProperties(TextLines& header, PlyHeader& h) {
  for (const PlyElement& e : h.elements) {
    if (e.name == "vertex") {
      h.vertexElement = &e;
      for (size_t p = 0; p < e.properties.size(); ++p) {
        for (int k = 0; k < 3; ++k) {
          if (e.properties[p].name == std::string(1, "xyz"[k]) && !e.properties[p].list)
            h.xyz[k] = static_cast<int>(p);
        }
      }
      if (h.xyz[0] < 0 || h.xyz[1] < 0 || h.xyz[2] < 0)
        header.fail(e.headerLine, "the vertex element needs x, y and z properties");
    } else if (e.name == "face") {
      h.faceElement = &e;
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const PlyProperty& q = e.properties[p];
        if (q.list && (q.name == "vertex_indices" || q.name == "vertex_index"))
          h.indexProperty = static_cast<int>(p);
      }
      if (h.indexProperty < 0)
        header.fail(e.headerLine, "the face element needs a list property 'vertex_indices'");
    }
  }
  if (!h.vertexElement || !h.faceElement)
    throw InputError(h.name, 0, "a PLY surface needs a vertex and a face element");
}

// Each record takes at least a line (ascii) or its fixed-size part (binary): counts beyond the
// file are refused before anything is allocated.
void countPlyBytesNeeded(TextLines& header, PlyHeader& h) {
  for (const PlyElement& e : h.elements) {
    unsigned long long record = h.ascii ? 1 : 0;
    for (const PlyProperty& p : e.properties) {
      if (!h.ascii) record += plySize(p.list ? p.countType : p.type);
    }
    if (record > 0 &&
        e.count > (std::numeric_limits<unsigned long long>::max() - h.needed) / record)
      header.fail(e.headerLine, "element count " + std::to_string(e.count) + " is too large");
    h.needed += e.count * record;
  }
}

PlyHeader readPlyHeader(const std::string& name, const std::string& text) {
  PlyHeader h;
  h.name = name;
  // The header is text up to and including the end_header line.
  const size_t end = text.find("end_header");
  if (text.rfind("ply", 0) != 0 || end == std::string::npos)
    throw InputError(name, 1, "not a PLY file (it must start with 'ply' and have 'end_header')");
  size_t bodyStart = text.find('\n', end);
  bodyStart = bodyStart == std::string::npos ? text.size() : bodyStart + 1;
  h.bodyStart = bodyStart;
  TextLines header(name, std::string_view(text).substr(0, bodyStart), 0);
  header.next("ply");
  const TextLine& format = header.next("the format line");
  if (format.tokens.size() != 3 || format.tokens[0] != "format" || format.tokens[2] != "1.0")
    header.fail(format.number,
                "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  const std::string_view kind = format.tokens[1];
  h.ascii = kind == "ascii";
  if (!h.ascii && kind != "binary_little_endian" && kind != "binary_big_endian")
    header.fail(format.number, "unknown PLY format '" + std::string(kind) + "'");
  h.bigEndian = kind == "binary_big_endian";
  for (;;) {
    const TextLine& line = header.next("end_header");
    const std::string_view key = line.tokens[0];
    if (key == "end_header") {
      h.endHeaderLine = line.number;
      break;
    }
    if (key == "comment" || key == "obj_info") continue;
    if (key == "element") {
      if (line.tokens.size() != 3) header.fail(line.number, "expected 'element NAME COUNT'");
      const long long count = header.parseInt(line, 2, "the element count");
      if (count < 0) header.fail(line.number, "negative element count");
      h.elements.push_back(
          {std::string(line.tokens[1]), static_cast<unsigned long long>(count), {}, line.number});
    } else if (key == "property") {
      if (h.elements.empty()) header.fail(line.number, "a property before any element");
      h.elements.back().properties.push_back(readPlyProperty(header, line));
    } else {
      header.fail(line.number, "unknown header keyword '" + std::string(key) + "'");
    }
  }
  findPlySurfaceProperties(header, h);
  countPlyBytesNeeded(header, h);
  return h;
}

void readPlyAsciiBody(const PlyHeader& h, const std::string& text, RawSurface& s) {
  std::vector<int> corner;
  TextLines body(h.name, text, 0);
  while (body.peek() && body.peek()->number <= h.endHeaderLine) body.next("the header");
  if (h.needed > body.remaining())
    throw InputError(h.name, h.endHeaderLine,
                     "the header promises " + std::to_string(h.needed) + " records, the file has " +
                         std::to_string(body.remaining()) + " more lines");
  for (const PlyElement& e : h.elements) {
    for (unsigned long long r = 0; r < e.count; ++r) {
      const TextLine& line =
          body.next(e.name + " " + std::to_string(r + 1) + " of " + std::to_string(e.count));
      size_t token = 0;
      Vec3 p = Vec3::Zero();
      for (size_t q = 0; q < e.properties.size(); ++q) {
        const PlyProperty& prop = e.properties[q];
        if (!prop.list) {
          if (token >= line.tokens.size())
            body.fail(line.number, "expected " + std::to_string(e.properties.size()) +
                                       " values, the line ends after " + std::to_string(token));
          const double value = body.parseDouble(line, token++, "a value");
          if (&e == h.vertexElement) {
            for (int k = 0; k < 3; ++k)
              if (h.xyz[k] == static_cast<int>(q)) p[k] = value;
          }
          continue;
        }
        const long long n = body.parseInt(line, token++, "a list count");
        if (n < 0 || static_cast<unsigned long long>(n) > line.tokens.size() - token)
          body.fail(line.number, "the list holds " + std::to_string(n) +
                                     " items but the line has " +
                                     std::to_string(line.tokens.size() - token) + " more values");
        const bool indices = &e == h.faceElement && static_cast<int>(q) == h.indexProperty;
        if (indices) corner.clear();
        for (long long k = 0; k < n; ++k) {
          const double value = body.parseDouble(line, token++, "a list item");
          if (indices)
            corner.push_back(checkedIndex(
                value, h.vertexCount(), [&](const std::string& m) { body.fail(line.number, m); }));
        }
        if (indices) {
          if (n < 3)
            body.fail(line.number, "a face needs at least 3 corners, got " + std::to_string(n));
          addFan(corner, s.faces);
        }
      }
      if (token != line.tokens.size())
        body.fail(line.number, "unexpected data after the " + std::to_string(token) + " values");
      if (&e == h.vertexElement) s.vertices.push_back(p);
    }
  }
  if (!body.atEnd()) body.fail(body.peek()->number, "unexpected data after the last element");
}

void readPlyBinaryBody(const PlyHeader& h, const std::string& text, RawSurface& s) {
  std::vector<int> corner;
  PlyBinary in(text, h.bodyStart, h.bigEndian, h.name);
  if (h.needed > in.remaining())
    throw InputError(h.name + ": the header promises at least " + std::to_string(h.needed) +
                     " bytes of data, the file has " + std::to_string(in.remaining()));
  for (const PlyElement& e : h.elements) {
    for (unsigned long long r = 0; r < e.count; ++r) {
      Vec3 p = Vec3::Zero();
      for (size_t q = 0; q < e.properties.size(); ++q) {
        const PlyProperty& prop = e.properties[q];
        const size_t at = in.offset();
        if (!prop.list) {
          const double value = in.read(prop.type, "a value");
          if (&e == h.vertexElement) {
            for (int k = 0; k < 3; ++k)
              if (h.xyz[k] == static_cast<int>(q)) p[k] = value;
          }
          continue;
        }
        const double n = in.read(prop.countType, "a list count");
        if (n < 0 ||
            n * static_cast<double>(plySize(prop.type)) > static_cast<double>(in.remaining()))
          in.fail(at, "a list of " + std::to_string(static_cast<long long>(n)) +
                          " items runs past the end of the file");
        const bool indices = &e == h.faceElement && static_cast<int>(q) == h.indexProperty;
        if (indices) corner.clear();
        for (long long k = 0; k < static_cast<long long>(n); ++k) {
          const size_t itemAt = in.offset();
          const double value = in.read(prop.type, "a list item");
          if (indices)
            corner.push_back(checkedIndex(value, h.vertexCount(),
                                          [&](const std::string& m) { in.fail(itemAt, m); }));
        }
        if (indices) {
          if (n < 3)
            in.fail(at, "a face needs at least 3 corners, got " +
                            std::to_string(static_cast<long long>(n)));
          addFan(corner, s.faces);
        }
      }
      if (&e == h.vertexElement) {
        if (!p.allFinite()) in.fail(in.offset(), "non-finite vertex coordinate");
        s.vertices.push_back(p);
      }
    }
  }
  if (in.remaining() != 0)
    in.fail(in.offset(), "unexpected data after the last element (" +
                             std::to_string(in.remaining()) + " bytes)");
}

}  // namespace

RawSurface readPly(const fs::path& path) {
  const std::string name = path.string();
  const std::string text = readWholeFile(path);
  const PlyHeader header = readPlyHeader(name, text);
  RawSurface s;
  if (header.ascii)
    readPlyAsciiBody(header, text, s);
  else
    readPlyBinaryBody(header, text, s);
  return s;
}

}  // namespace galsculpt
