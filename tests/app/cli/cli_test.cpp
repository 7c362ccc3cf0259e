#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "app/cli/cli_args.h"
#include "app/cli/command_table.h"
#include "tests/app/cli/cli_run.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::run;

TEST(Cli, HelpAndVersion) {
  EXPECT_EQ(run({"--help"}).code, kExitOk);
  EXPECT_NE(run({"help"}).out.find("mesh import SURFACE OUT --tets N"), std::string::npos);
  EXPECT_NE(run({"--version"}).out.find("galsculpt "), std::string::npos);
}

TEST(Cli, EveryCommandHasHelpFromTheTableThatParsesIt) {
  const std::string top = run({"--help"}).out;
  for (const CommandSpec& c : commandTable()) {
    std::vector<std::string> words;
    for (size_t at = 0; at != std::string::npos;) {
      const size_t space = c.name.find(' ', at);
      words.push_back(c.name.substr(at, space == std::string::npos ? space : space - at));
      at = space == std::string::npos ? space : space + 1;
    }
    for (const char* flag : {"--help", "-h"}) {
      std::vector<std::string> args = words;
      args.push_back(flag);
      const CliRun r = run(args);
      EXPECT_EQ(r.code, kExitOk) << c.name << ' ' << flag << ": " << r.err;
      EXPECT_EQ(r.out.rfind("usage: " + wrapUsage(commandUsage(c), 93, 10) + "\n", 0), 0u) << r.out;
      // Every flag the parser takes, with its meaning; -h anywhere on the line.
      for (const FlagSpec& f : c.flags) {
        EXPECT_NE(r.out.find("  " + f.name + (f.value.empty() ? "" : " " + f.value)),
                  std::string::npos)
            << c.name << ": " << f.name;
        EXPECT_FALSE(f.help.empty()) << c.name << ": " << f.name;
      }
    }
    EXPECT_NE(top.find(wrapUsage(commandUsage(c), 98, 8)), std::string::npos)
        << "the top-level help: " << c.name;
    // What the help lists, the parser takes: each flag is known (a wrong value or a missing
    // operand may still be refused, but never as an unknown option).
    for (const FlagSpec& f : c.flags) {
      std::vector<std::string> args;
      args.push_back(f.name);
      if (!f.value.empty()) args.push_back("x");
      try {
        const CliArgs parsed(args, c);
        EXPECT_TRUE(parsed.has(f.name));
      } catch (const UsageError& e) {
        EXPECT_EQ(std::string(e.what()).find("unknown option"), std::string::npos)
            << c.name << ' ' << f.name;
      }
    }
  }
  // Help after other arguments too, and for a group.
  EXPECT_EQ(run({"run", "scene.json", "--frames", "3", "-h"}).code, kExitOk);
  const CliRun mesh = run({"mesh", "--help"});
  EXPECT_EQ(mesh.code, kExitOk);
  for (const char* sub : {"mesh info", "mesh convert", "mesh import", "mesh generate"})
    EXPECT_NE(mesh.out.find(sub), std::string::npos) << sub;
}

TEST(Cli, UsageErrorsSayErrorTheUsageAndTheNearestName) {
  const CliRun frame = run({"run", "scene.json", "--frame", "3", "--out", "o"});
  EXPECT_EQ(frame.code, kExitUsage);
  EXPECT_EQ(frame.err.rfind("galsculpt: error: unknown option --frame for run (did you mean "
                            "--frames?)\nusage: galsculpt run SCENE --frames N --out DIR [",
                            0),
            0u)
      << frame.err;
  EXPECT_NE(frame.err.find("(run 'galsculpt run --help' for what each option means)"),
            std::string::npos);
  EXPECT_NE(run({"rnu"}).err.find("unknown command 'rnu' (did you mean run?)"), std::string::npos);
  EXPECT_NE(run({"mesh", "imprt"}).err.find("(did you mean import?)"), std::string::npos);
  EXPECT_NE(run({"bench", "--sweeep"}).err.find("(did you mean --sweep?)"), std::string::npos);
  // Nothing near: no guess.
  const CliRun far = run({"bench", "--zzzzzzzz"});
  EXPECT_EQ(far.code, kExitUsage);
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
  // --metrics is optional in the usage; --frames and --out are not.
  EXPECT_NE(commandUsage(commandSpec("run")).find("[--metrics FILE.csv]"), std::string::npos);
  EXPECT_EQ(
      run({"run", "scene.json", "--out", "o"}).err.find("galsculpt: error: run needs --frames N"),
      0u);
}

TEST(Cli, AMeshWhereASceneIsExpectedSaysWhatToDo) {
  const std::string mesh =
      (fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "meshes" / "sphere_small.node").string();
  const CliRun r = run({"run", mesh, "--frames", "1", "--out", "o"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("a mesh, not a scene: open it with 'galsculpt open"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("mesh.file"), std::string::npos) << r.err;
  // A surface: the scene key that meshes it.
  const CliRun surface = run({"play", "model.OBJ", "--out", "o"});
  EXPECT_EQ(surface.code, kExitBadInput);
  EXPECT_NE(surface.err.find("name it in a scene's mesh.import with mesh.tets"), std::string::npos)
      << surface.err;
  test::TempDir dir;
  const fs::path script = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scripts" / "sphere_cut.json";
  EXPECT_NE(run({"run", script.string(), "--frames", "1", "--out", (dir / "o").string()})
                .err.find("this looks like a playback script: galsculpt play FILE"),
            std::string::npos);
}

TEST(CommandTable, AUsageWrapsOnlyBeforeAnOption) {
  const std::string usage =
      "galsculpt run SCENE --frames N --out DIR [--metrics FILE.csv] [--size WxH]";
  EXPECT_EQ(wrapUsage(usage, 200, 4), usage);
  EXPECT_EQ(wrapUsage(usage, 40, 4),
            "galsculpt run SCENE --frames N --out DIR\n    [--metrics FILE.csv] [--size WxH]");
  // A piece longer than the width stays whole on its own line.
  EXPECT_EQ(
      wrapUsage(usage, 10, 2),
      "galsculpt run SCENE\n  --frames N\n  --out DIR\n  [--metrics FILE.csv]\n  [--size WxH]");
}

TEST(CommandTable, TheNearestNameIsASlipOrNothing) {
  const std::vector<std::string> flags{"--frames", "--out", "--export-every", "--export-tets"};
  EXPECT_EQ(nearestName("--frame", flags), "--frames");
  EXPECT_EQ(nearestName("--fames", flags), "--frames");
  EXPECT_EQ(nearestName("--export-tet", flags), "--export-tets");
  EXPECT_EQ(nearestName("--outt", flags), "--out");
  EXPECT_EQ(nearestName("--zzzzzz", flags), "");
  EXPECT_EQ(nearestName("strenght", {"strength", "radius"}), "strength");
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run({"frobnicate"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh", "info"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh", "info", "a.node", "--bogus"}).code, kExitUsage);
  const CliRun r = run({"mesh", "import", "a.obj", "b.node"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("needs --tets N"), std::string::npos);
  EXPECT_EQ(run({"mesh", "import", "a.obj", "b.node", "--tets", "ten"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh", "convert", "a.node", "b.docx"}).code, kExitUsage);
}

TEST(Cli, BadInputExitsThreeWithFileAndLine) {
  const fs::path broken = fs::path(GALSCULPT_TEST_DATA) / "broken" / "nan_coordinate.node";
  const CliRun r = run({"mesh", "info", broken.string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("nan_coordinate.node:3: coordinate is not finite"), std::string::npos)
      << r.err;
  EXPECT_EQ(run({"mesh", "info", "/nonexistent/x.obj"}).code, kExitBadInput);
}

}  // namespace
}  // namespace galsculpt
