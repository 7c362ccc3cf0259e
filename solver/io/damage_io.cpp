#include "solver/io/damage_io.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"
#include "solver/io/text_lines.h"

namespace galsculpt {

namespace {

void writeDamageTo(std::ostream& out, const std::vector<Edge>& edges,
                   const std::vector<std::uint8_t>& damaged, const std::vector<float>& crossing,
                   const std::string& stampLine);

void checkSizes(const std::filesystem::path& path, const std::vector<Edge>& edges,
                const std::vector<std::uint8_t>& damaged, const std::vector<float>& crossing) {
  if (damaged.size() != edges.size()) {
    throw OutputError("cannot write " + path.string() + ": one damage flag per edge is needed");
  }
  if (!crossing.empty() && crossing.size() != edges.size()) {
    throw OutputError("cannot write " + path.string() + ": one crossing per edge is needed");
  }
}

}  // namespace

void writeDamage(const std::filesystem::path& path, const std::vector<Edge>& edges,
                 const std::vector<std::uint8_t>& damaged, const std::vector<float>& crossing) {
  checkSizes(path, edges, damaged, crossing);
  writeFileAtomically(path,
                      [&](std::ostream& out) { writeDamageTo(out, edges, damaged, crossing, ""); });
}

void addDamage(FileSet& set, const std::filesystem::path& path, const std::vector<Edge>& edges,
               const std::vector<std::uint8_t>& damaged, const std::vector<float>& crossing) {
  checkSizes(path, edges, damaged, crossing);
  set.add(path, [&](std::ostream& out) {
    writeDamageTo(out, edges, damaged, crossing, set.stampLine());
  });
}

namespace {

void writeDamageTo(std::ostream& out, const std::vector<Edge>& edges,
                   const std::vector<std::uint8_t>& damaged, const std::vector<float>& crossing,
                   const std::string& stampLine) {
  const auto count = std::count_if(damaged.begin(), damaged.end(), [](auto d) { return d != 0; });
  {
    // 9 significant digits bring a float back bit for bit.
    out << std::setprecision(9) << "# galsculpt damage 2\n" << count << '\n';
    for (size_t e = 0; e < edges.size(); ++e) {
      if (!damaged[e]) continue;
      out << edges[e][0] << ' ' << edges[e][1];
      if (!crossing.empty() && hasCrossing(crossing[e])) out << ' ' << crossing[e];
      out << '\n';
    }
    out << stampLine;
  }
}

}  // namespace

EdgeDamageState readDamage(const std::filesystem::path& path, const std::vector<Edge>& edges) {
  const std::string text = readWholeFile(path);  // TextLines keeps views into it
  TextLines lines(path.string(), text);
  const std::string stamp = findSetStamp(text);
  const TextLine& header = lines.next("the number of damaged edges");
  if (header.tokens.size() != 1) lines.fail(header.number, "expected the number of damaged edges");
  const long long count = lines.parseInt(header, 0, "the number of damaged edges");
  if (count < 0 || count > static_cast<long long>(edges.size())) {
    lines.fail(header.number, "the mesh has " + std::to_string(edges.size()) +
                                  " edges; cannot damage " + std::to_string(count));
  }
  EdgeDamageState state{std::vector<std::uint8_t>(edges.size(), 0),
                        std::vector<float>(edges.size(), kNoCrossing), stamp};
  for (long long i = 0; i < count; ++i) {
    const TextLine& line = lines.next("a damaged edge (two vertex numbers)");
    if (line.tokens.size() != 2 && line.tokens.size() != 3)
      lines.fail(line.number, "expected two vertex numbers and, optionally, where a blade crossed");
    long long a = lines.parseInt(line, 0, "a vertex number");
    long long b = lines.parseInt(line, 1, "a vertex number");
    float at = kNoCrossing;
    if (line.tokens.size() == 3) {
      const double value = lines.parseDouble(line, 2, "where a blade crossed the edge");
      if (!(value >= 0.0 && value <= 1.0))
        lines.fail(line.number, "where a blade crossed the edge must be a fraction in [0, 1]");
      at = static_cast<float>(value);
    }
    if (a > b) {
      std::swap(a, b);
      if (hasCrossing(at)) at = 1.0f - at;
    }
    const Edge key{static_cast<int>(a), static_cast<int>(b)};
    const auto it = std::lower_bound(edges.begin(), edges.end(), key);
    if (a < 0 || it == edges.end() || *it != key) {
      std::ostringstream what;
      what << '(' << a << ", " << b << ") is not an edge of the mesh";
      lines.fail(line.number, what.str());
    }
    std::uint8_t& flag = state.damaged[it - edges.begin()];
    if (flag) lines.fail(line.number, "edge listed twice");
    flag = 1;
    state.crossing[it - edges.begin()] = at;
  }
  if (!lines.atEnd()) {
    lines.fail(lines.peek()->number,
               "more edges than the count on line " + std::to_string(header.number) + " says");
  }
  return state;
}

std::vector<double> tetDamageFraction(const std::vector<std::array<int, 6>>& tetEdges,
                                      const std::vector<std::uint8_t>& damaged) {
  std::vector<double> out(tetEdges.size(), 0.0);
  for (size_t t = 0; t < tetEdges.size(); ++t) {
    int n = 0;
    for (int e : tetEdges[t]) n += damaged[e] != 0;
    out[t] = n / 6.0;
  }
  return out;
}

}  // namespace galsculpt
