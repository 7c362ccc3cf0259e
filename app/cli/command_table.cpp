#include "app/cli/command_table.h"

#include "app/cli/cli_args.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace galsculpt {

namespace {

const FlagSpec kBackend{"--backend", "auto|cpu|cuda|device-like",
                        "the solver's backend (default: the scene's; auto: CUDA where there is a "
                        "GPU, else the CPU; device-like: the GPU's paths on the CPU, counted)"};
const FlagSpec kThreads{"--threads", "N",
                        "the CPU's threads (default: GALSCULPT_THREADS, else OMP_NUM_THREADS, "
                        "else every core)"};
const FlagSpec kSolverOption{"--solver-option", "KEY=VALUE[,...]",
                             "solver keys over the scene's own (docs/scenes.md, solver)"};
const FlagSpec kSize{"--size", "WxH", "image size in pixels (default 1280x800)"};
const FlagSpec kSolver{"--solver", "reference",
                       "replace the scene's solver with the reference (Newton, direct solve)"};
const FlagSpec kMetrics{"--metrics", "FILE.csv", "the metrics CSV (default DIR/metrics.csv)"};
const FlagSpec kExportEvery{"--export-every", "K", "export the surface every K frames too"};
const FlagSpec kExportFormat{"--export-format", "obj|ply|stl|gltf|glb",
                             "the surfaces' format (default obj)"};
const FlagSpec kExportTets{"--export-tets", "",
                           "also write the tet mesh at the end with its damage (DIR/final.node, "
                           ".ele, .face, .damage, .vtk)"};
const FlagSpec kPngEvery{"--png-every", "K", "render the surface to DIR every K frames"};
const FlagSpec kTets{"--tets", "N", "the number of tets to mesh for"};
const FlagSpec kTimeout{"--timeout", "S", "seconds each TetGen attempt may take (default 300)"};
const FlagSpec kTolerance{"--tolerance", "F",
                          "how far from N the count may be, as a fraction (default 0.15)"};
const FlagSpec kQuality{"--quality", "Q", "TetGen's radius-edge bound (default 1.414)"};

FlagSpec required(FlagSpec flag) {
  flag.required = true;
  return flag;
}

// `text` from column `column` on, wrapped at `width` columns between words, its later lines
// starting at `column` too.
std::string wrapWords(const std::string& text, size_t column, size_t width) {
  std::istringstream words(text);
  std::string out;
  size_t at = column;
  bool first = true;
  for (std::string word; words >> word;) {
    if (!first && at + 1 + word.size() > width) {
      out.push_back('\n');
      out.append(column, ' ');
      at = column;
      first = true;
    }
    if (!first) out.push_back(' ');
    out.append(word);
    at += word.size() + (first ? 0 : 1);
    first = false;
  }
  return out;
}

std::vector<CommandSpec> makeTable() {
  return {
      {"open",
       "[FILE]",
       0,
       1,
       "open a project (.gsproj), scene (.json), playback script, tet mesh or surface mesh in "
       "the sculpting window (default: the default scene); with no display or --headless, "
       "render its standard views into DIR",
       {{"--headless", "", "render the views offscreen instead of opening a window"},
        {"--out", "DIR", "where headless views go (default galsculpt-out)"},
        kSize,
        {"--paused", "", "start with the simulation paused (space plays)"},
        {"--input-script", "FILE", "drive the window with synthetic input (docs/user-guide.md)"},
        {"--save-project", "FILE", "save the session as a project when the window closes"},
        {"--save-recording", "FILE", "save the session's recording when the window closes"},
        {"--autosave", "SECONDS", "autosave period for crash recovery (default 60; 0: never)"},
        {"--no-recovery", "", "do not offer files left by a crash"},
        kBackend,
        kThreads,
        kSolverOption}},
      {"render",
       "FILE",
       1,
       1,
       "render a scene, project or mesh offscreen (EGL) from the standard views into PNG files",
       {required({"--out", "DIR", "the folder for the images"}), kSize}},
      {"run",
       "SCENE",
       1,
       1,
       "simulate a scene headless: a metrics CSV row per frame, the final surface (and more on "
       "request)",
       {required({"--frames", "N", "frames to simulate"}),
        required({"--out", "DIR", "the folder for what the run writes"}), kSolver, kMetrics,
        kExportEvery, kExportFormat, kExportTets, kPngEvery, kSize, kBackend, kThreads,
        kSolverOption}},
      {"play",
       "SCRIPT",
       1,
       1,
       "play a playback script (a scene and timed knife, brush and anchor events) headless, as "
       "run does",
       {required({"--out", "DIR", "the folder for what the run writes"}), kExportEvery, kMetrics,
        kSolver, kExportFormat, kExportTets, kPngEvery, kSize, kBackend, kThreads, kSolverOption}},
      {"bench",
       "",
       0,
       0,
       "speed against error: the scenes' solvers against the reference, a row per setting",
       {{"--scene", "NAME[,NAME...]", "the scenes to measure (default: all of them)"},
        {"--quick", "", "fewer frames and settings"},
        {"--sweep", "", "on the sphere, a sweep of grids and sweeps too"},
        {"--cracks", "", "the cost of a frame against the number of knife cuts"},
        {"--frames", "N", "measured frames (default 60; 20 with --quick)"},
        {"--settle", "N[,N...]", "untimed frames before the measured ones (several: windows)"},
        {"--json", "FILE", "also write the results as JSON"},
        kBackend,
        {"--debris", "keep|remove", "every run's debris rule instead of the scene's"},
        {"--preset", "converged|paper", "every scene read with that solver preset"},
        kThreads,
        {"--reference-dir", "DIR", "keep and reuse each scene's reference run there"},
        kSolverOption}},
      {"mesh info",
       "FILE",
       1,
       1,
       "what a tet or surface mesh holds: counts, box, volume, quality, watertightness, shells, "
       "pieces",
       {{"--json", "", "as JSON"}}},
      {"mesh convert",
       "IN OUT",
       2,
       2,
       "convert between .node/.ele, .msh, .vtk and .obj/.ply/.stl/.gltf/.glb (a surface to tets "
       "through TetGen)",
       {kTets, kTimeout, kTolerance, kQuality}},
      {"mesh import",
       "SURFACE OUT",
       2,
       2,
       "tetrahedralize a closed surface with TetGen into about N tets, keeping its shape",
       {required(kTets), kTimeout, kTolerance, kQuality}},
      {"mesh generate",
       "sphere|charpy|steak OUT",
       2,
       2,
       "the paper's shapes: a tet mesh of N tets, or the closed surface resolved for N tets",
       {{"--tets", "N", "the number of tets (default: the paper's)"},
        {"--radius", "R", "the sphere's radius in m (default 0.1)"},
        kTimeout}},
      {"scene check",
       "SCENE",
       1,
       1,
       "validate a scene file and print a summary",
       {{"--load-mesh", "", "also build its mesh and check the anchors against it"}}},
  };
}

}  // namespace

const std::vector<CommandSpec>& commandTable() {
  static const std::vector<CommandSpec> table = makeTable();
  return table;
}

const CommandSpec& commandSpec(const std::string& name) {
  for (const CommandSpec& c : commandTable())
    if (c.name == name) return c;
  throw std::invalid_argument("no command '" + name + "'");
}

std::string commandUsage(const CommandSpec& command) {
  std::string usage = "galsculpt " + command.name;
  if (!command.operands.empty()) usage += " " + command.operands;
  auto flagText = [](const FlagSpec& f) {
    return f.value.empty() ? f.name : f.name + " " + f.value;
  };
  for (const FlagSpec& f : command.flags)
    if (f.required) usage.append(" ").append(flagText(f));
  for (const FlagSpec& f : command.flags)
    if (!f.required) usage.append(" [").append(flagText(f)).append("]");
  return usage;
}

std::string wrapUsage(const std::string& usage, size_t width, size_t indent) {
  std::vector<std::string> pieces;  // each starts at a break: before " [" or " -"
  size_t start = 0;
  for (size_t i = 1; i + 1 < usage.size(); ++i) {
    if (usage[i] == ' ' && (usage[i + 1] == '[' || usage[i + 1] == '-')) {
      pieces.push_back(usage.substr(start, i - start));
      start = i + 1;
    }
  }
  pieces.push_back(usage.substr(start));
  std::string out;
  size_t column = 0;
  for (const std::string& piece : pieces) {
    if (out.empty()) {
      out = piece;
      column = piece.size();
    } else if (column + 1 + piece.size() > width) {
      out.push_back('\n');
      out.append(indent, ' ').append(piece);
      column = indent + piece.size();
    } else {
      out.push_back(' ');
      out.append(piece);
      column += 1 + piece.size();
    }
  }
  return out;
}

std::string commandHelp(const CommandSpec& command) {
  std::ostringstream s;
  s << "usage: " << wrapUsage(commandUsage(command), 100 - 7, 10) << "\n\n"
    << wrapWords(command.summary, 0, 100) << "\n";
  if (!command.flags.empty()) s << "\noptions:\n";
  constexpr size_t kColumn = 26, kWidth = 100;
  for (const FlagSpec& f : command.flags) {
    const std::string head = "  " + f.name + (f.value.empty() ? "" : " " + f.value);
    s << head;
    if (head.size() + 2 <= kColumn) {
      s << std::string(kColumn - head.size(), ' ');
    } else {
      s << "\n" << std::string(kColumn, ' ');
    }
    s << wrapWords((f.required ? "(required) " : "") + f.help, kColumn, kWidth) << '\n';
  }
  s << "  -h, --help              this text\n";
  s << "\ndocs/cli.md has the whole story; exit codes: 0 ok, 1 failure, 2 usage, 3 bad input, 4 "
       "output not written\n";
  return s.str();
}

std::string topLevelHelp() {
  std::ostringstream s;
  s << "usage: galsculpt [COMMAND] [ARGS]\n\n"
       "With no command, opens the default scene (a window; with no display, a headless run that\n"
       "writes images and says where).\n\ncommands:\n";
  for (const CommandSpec& c : commandTable()) {
    s << "  " << wrapUsage(commandUsage(c), 98, 8) << "\n      " << wrapWords(c.summary, 6, 100)
      << "\n";
  }
  s << "  help, --help, -h; version, --version\n"
       "\n'galsculpt COMMAND --help' says what each option means (docs/cli.md has more).\n"
       "\nexit codes: 0 ok, 1 failure, 2 usage, 3 bad input, 4 output not written\n";
  return s.str();
}

std::string subcommandOf(const std::string& group, const std::vector<std::string>& args) {
  std::vector<std::string> words;
  std::ostringstream list;
  list << "usage: galsculpt " << group << " SUBCOMMAND ...\n\nsubcommands:\n";
  for (const CommandSpec& c : commandTable()) {
    if (c.name.rfind(group + " ", 0) != 0) continue;
    words.push_back(c.name.substr(group.size() + 1));
    list << "  " << wrapUsage(commandUsage(c), 98, 8) << "\n      " << wrapWords(c.summary, 6, 100)
         << "\n";
  }
  list << "\n'galsculpt " << group << " SUBCOMMAND --help' says what each option means.\n";
  if (args.empty() || args[0] == "-h" || args[0] == "--help") {
    if (args.empty()) throw UsageError(group + " needs a subcommand:\n" + list.str(), "");
    throw HelpRequested(list.str());
  }
  if (std::find(words.begin(), words.end(), args[0]) != words.end()) return group + " " + args[0];
  throw UsageError("unknown " + group + " subcommand '" + args[0] + "'" +
                   didYouMean(args[0], words));
}

std::string nearestName(const std::string& word, const std::vector<std::string>& candidates) {
  // Edits to turn one into the other, a swap of two neighbours counting one ("rnu" for "run").
  auto distance = [](const std::string& a, const std::string& b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
      for (size_t j = 1; j <= b.size(); ++j) {
        d[i][j] =
            std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
        if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
          d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
    return d[a.size()][b.size()];
  };
  std::string best;
  size_t bestDistance = std::max<size_t>(1, word.size() / 3) + 1;
  for (const std::string& c : candidates) {
    const size_t d = distance(word, c);
    // A prefix ("--frame" for "--frames") is a slip whatever its length.
    const bool prefix =
        c.size() > word.size() && c.compare(0, word.size(), word) == 0 && word.size() >= 4;
    if (d < bestDistance || (prefix && best.empty())) {
      best = c;
      bestDistance = d;
    }
  }
  return best;
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string near = nearestName(word, candidates);
  return near.empty() ? "" : " (did you mean " + near + "?)";
}

}  // namespace galsculpt
