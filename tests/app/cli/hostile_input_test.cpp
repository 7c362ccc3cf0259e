// Hostile input through the real command line: the committed corpus (tests/data/hostile), cases
// too large or too binary to commit (generated here), file sets killed mid-write, and the
// headless `open` paths. Every malformed input must end in the documented exit code with a
// message naming the file and the place; none may crash, hang or be accepted.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "app/cli/cli.h"
#include "engine/scene/scene_mesh.h"
#include "engine/session/project_file.h"
#include "engine/surface/surface_io.h"
#include "solver/io/folder_lock.h"
#include "solver/io/tetgen_io.h"
#include "solver/mesh/shape_generators.h"
#include "tests/app/cli/cli_run.h"
#include "tests/project_bytes.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(GALSCULPT_TEST_DATA) / "hostile";
const fs::path kAssets = fs::path(GALSCULPT_SOURCE_DIR) / "assets";

using test::CliRun;
CliRun run(const std::vector<std::string>& args) {
  return test::runCliCapture(args);
}

std::vector<std::string> split(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

TEST(HostileInput, TheCommittedCorpusIsRefusedWithFileAndPlace) {
  test::TempDir dir;
  std::ifstream manifest(kCorpus / "cases.tsv");
  ASSERT_TRUE(manifest) << "tests/data/hostile/cases.tsv";
  std::set<fs::path> named;
  int cases = 0;
  for (std::string line; std::getline(manifest, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cols;
    std::istringstream fields(line);
    for (std::string c; std::getline(fields, c, '\t');) cols.push_back(c);
    if (cols.size() == 3) cols.push_back("");  // an accepted case: no message to look for
    ASSERT_EQ(cols.size(), 4u) << line;
    const fs::path file = kCorpus / cols[1];
    named.insert(fs::path(cols[1]).replace_extension());
    std::vector<std::string> args;
    for (std::string a : split(cols[0])) {
      if (a == "FILE") a = file.string();
      if (a.rfind("OUT", 0) == 0)
        a = (dir / ("out" + std::to_string(cases))).string() + a.substr(3);  // OUT, OUT.node
      args.push_back(a);
    }
    const CliRun r = run(args);
    EXPECT_EQ(r.code, std::stoi(cols[2])) << cols[1] << ": " << r.err;
    EXPECT_NE(r.err.find(cols[3]), std::string::npos) << cols[1] << ": " << r.err;
    ++cases;
  }
  EXPECT_GE(cases, 60);
  // Every file is a case, or the companion of one (same stem: a TetGen set, a glTF's buffer).
  for (const auto& entry : fs::recursive_directory_iterator(kCorpus)) {
    if (!entry.is_regular_file() || entry.path().filename() == "cases.tsv") continue;
    const fs::path stem = fs::relative(entry.path(), kCorpus).replace_extension();
    EXPECT_TRUE(named.count(stem)) << entry.path() << " is in the corpus but no case names it";
  }
}

// Cases too large to commit, or that are not plain files.
TEST(HostileInput, GeneratedCasesAreRefused) {
  test::TempDir dir;
  // 200,000 levels of nesting (it once overflowed the stack while parsing).
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  test::writeText(dir / "deep_scene.json", "{\"name\": \"x\", \"solver\": " + deep + "}");
  CliRun r = run({"scene", "check", (dir / "deep_scene.json").string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("deep_scene.json:1: JSON nests deeper than 256 levels"), std::string::npos)
      << r.err;
  test::writeText(dir / "deep_script.json", "{\"scene\": \"" +
                                                (kAssets / "scenes" / "default.json").string() +
                                                "\", \"frames\": 1, \"events\": " + deep + "}");
  r = run({"play", (dir / "deep_script.json").string(), "--out", (dir / "o").string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("deep_script.json:1: JSON nests deeper"), std::string::npos) << r.err;

  // A glTF whose JSON nests 200,000 deep: assimp's recursive parser overflowed the stack.
  const std::string gltf = "{\"asset\": {\"version\": \"2.0\"}, \"x\": " + deep + "}";
  test::writeText(dir / "deep.gltf", gltf);
  r = run({"mesh", "info", (dir / "deep.gltf").string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("deep.gltf: byte 290: JSON nests deeper than 256 levels"), std::string::npos)
      << r.err;
  std::string chunk = gltf;
  chunk.resize((chunk.size() + 3) / 4 * 4, ' ');
  std::string glb = "glTF";
  auto u32 = [&glb](std::uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
  u32(2);
  u32(static_cast<std::uint32_t>(20 + chunk.size()));
  u32(static_cast<std::uint32_t>(chunk.size()));
  glb += "JSON" + chunk;
  test::writeText(dir / "deep.glb", glb);
  r = run({"mesh", "info", (dir / "deep.glb").string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("deep.glb: byte 310: JSON nests deeper"), std::string::npos) << r.err;

  // A device and a folder where a mesh file should be (/dev/zero ended in std::bad_alloc).
  fs::create_symlink("/dev/zero", dir / "zero.node");
  fs::create_symlink("/dev/zero", dir / "zero.ele");
  r = run({"mesh", "info", (dir / "zero.node").string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("zero.node: is a character device, not a regular file"), std::string::npos)
      << r.err;
  fs::create_directories(dir / "folder.node");
  test::writeText(dir / "folder.ele", "1 4 0\n0 0 1 2 3\n");
  r = run({"mesh", "info", (dir / "folder.node").string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("folder.node: is a folder"), std::string::npos) << r.err;
}

// A project saved from a cut clay ball, and its damaged copies.
class HostileProjects : public ::testing::Test {
 protected:
  void SetUp() override {
    const fs::path script = kAssets / "scripts" / "sphere_cut.json";
    const CliRun r = run({"open", script.string(), "--headless", "--out", (dir / "views").string(),
                          "--save-project", good().string(), "--save-recording",
                          (dir / "rec.json").string(), "--size", "64x40"});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    bytes = test::readText(good());
  }
  fs::path good() const { return dir / "good.gsproj"; }
  std::string errorOf(const std::string& content, const std::string& name = "bad.gsproj") {
    test::writeText(dir / name, content);
    const CliRun r =
        run({"open", (dir / name).string(), "--headless", "--out", (dir / "v").string()});
    EXPECT_EQ(r.code, kExitBadInput) << name << ": " << r.err;
    return r.err;
  }
  std::string withHeader(const std::function<void(nlohmann::json&)>& edit) const {
    return test::withProjectHeader(bytes, edit);
  }
  std::string replaced(const std::string& from, const std::string& to) const {
    std::string s = bytes;
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  }
  test::TempDir dir;
  std::string bytes;
};

// `open` replays a playback script headless (it was refused: "$.mesh: is required"), and its
// --save-project and --save-recording write their files headless (they exited 0 and wrote
// nothing); --input-script needs the window and is refused headless.
TEST_F(HostileProjects, HeadlessOpenReplaysScriptsAndSavesWhatItIsAskedTo) {
  ASSERT_TRUE(fs::exists(good()));
  ASSERT_TRUE(fs::exists(dir / "rec.json"));
  const Project p = readProject(good());
  EXPECT_EQ(p.state.frame, 120) << "the script was replayed to its end";
  int damaged = 0;
  for (auto d : p.state.damaged) damaged += d;
  EXPECT_GT(damaged, 0) << "its knife cut";
  const CliRun replay = run({"play", (dir / "rec.json").string(), "--out", (dir / "p").string()});
  EXPECT_EQ(replay.code, kExitOk) << replay.err;
  const CliRun input = run({"open", good().string(), "--headless", "--input-script",
                            (dir / "rec.json").string(), "--out", (dir / "v").string()});
  EXPECT_EQ(input.code, kExitUsage);
  EXPECT_NE(input.err.find("--input-script drives the window"), std::string::npos) << input.err;
}

TEST_F(HostileProjects, MalformedProjectsAreRefusedWithFileAndPlace) {
  EXPECT_NE(errorOf(replaced("GALSCULPT PROJECT", "GALSCULPT PROJECX"))
                .find("bad.gsproj:1: not a Galsculpt project"),
            std::string::npos)
      << "a broken magic is a broken project, not 'unknown mesh format'";
  for (const char* version : {"1garbage", "1.9", "-1", ""}) {
    EXPECT_NE(errorOf(replaced("PROJECT 3\n", std::string("PROJECT ") + version + "\n"))
                  .find("bad.gsproj:1: the format version is not a whole number"),
              std::string::npos)
        << version;
  }
  EXPECT_NE(errorOf(bytes.substr(0, bytes.size() / 2)).find("bad.gsproj: truncated"),
            std::string::npos);
  // The plastic strain (a double per tet) is the last array before the solver carry: a NaN
  // there was accepted.
  size_t carry = 0;
  test::withProjectHeader(bytes, [&](nlohmann::json& h) { carry = h["solver_carry"]; });
  std::string nan = bytes;
  const double value = std::nan("");
  std::memcpy(&nan[nan.size() - (carry + 1) * sizeof(double)], &value, sizeof(double));
  EXPECT_NE(errorOf(nan).find("bad.gsproj: plastic strain: value"), std::string::npos);
  // An invalid scene inside names the project (it named the scene's recorded path).
  const std::string scene =
      errorOf(withHeader([](nlohmann::json& h) { h["scene"]["material"]["preset"] = "cheese"; }));
  EXPECT_NE(scene.find("bad.gsproj: $.scene (saved from"), std::string::npos) << scene;
  EXPECT_NE(scene.find("$.material.preset: unknown value 'cheese'"), std::string::npos) << scene;
  // An anchor without its vertices (found by the fuzzing run: the library's bare exception).
  EXPECT_NE(errorOf(withHeader([](nlohmann::json& h) {
              h["anchors"][0].erase("vertices");
            })).find("bad.gsproj: $.anchors[0].vertices: is required"),
            std::string::npos);
  // A 200,000-deep header.
  const size_t line1 = bytes.find('\n'), line2 = bytes.find('\n', line1 + 1);
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  EXPECT_NE(errorOf(bytes.substr(0, line1 + 1) + std::to_string(deep.size()) + "\n" + deep)
                .find("bad.gsproj:3: JSON nests deeper than 256 levels"),
            std::string::npos);
  (void)line2;
}

// `mesh convert/import/generate` take an output without extension as a TetGen basename.
TEST(HostileInput, AnOutputWithoutExtensionIsATetGenBasename) {
  test::TempDir dir;
  const CliRun r = run({"mesh", "convert", (kAssets / "meshes" / "sphere_small.node").string(),
                        (dir / "ball").string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  for (const char* ext : {".node", ".ele", ".face"})
    EXPECT_TRUE(fs::exists(dir / ("ball" + std::string(ext)))) << ext;
  EXPECT_EQ(run({"mesh", "info", (dir / "ball.node").string()}).code, kExitOk);
  // mesh import too (it was refused: "unknown output format ''").
  const CliRun import = run({"mesh", "import", (kAssets / "meshes" / "sphere_small.node").string(),
                             (dir / "again").string(), "--tets", "100"});
  EXPECT_EQ(import.code, kExitBadInput) << "a tet mesh is not a surface to import";
  const CliRun surface =
      run({"mesh", "convert", (kAssets / "meshes" / "sphere_small.node").string(),
           (dir / "ball.obj").string()});
  ASSERT_EQ(surface.code, kExitOk) << surface.err;
  const CliRun meshed = run(
      {"mesh", "import", (dir / "ball.obj").string(), (dir / "meshed").string(), "--tets", "3000"});
  ASSERT_EQ(meshed.code, kExitOk) << meshed.err;
  EXPECT_TRUE(fs::exists(dir / "meshed.node") && fs::exists(dir / "meshed.ele"));
}

// The tet mesh and its damage are one set: a reader never accepts a set mixed from two writes,
// whenever the writer is killed, and temporaries left by a killed writer are cleaned up.
TEST(HostileInput, KilledWritersNeverLeaveASetThatReadsAsOneMesh) {
  test::TempDir dir;
  // Two different meshes written in turn to the same stem.
  const fs::path a = kAssets / "meshes" / "sphere_small.node";
  TetMesh bar = test::gridBar(28, 28, 28, 0.01);  // about 0.1 s to write: kills land mid-write
  writeTetGen(dir / "bar", bar);
  const fs::path b = dir / "bar.node";
  const int verticesA = readTetGen(a).numVertices(), verticesB = bar.numVertices();
  ASSERT_EQ(run({"mesh", "convert", a.string(), (dir / "out.node").string()}).code, kExitOk);
  std::mt19937 rng(19);
  std::uniform_int_distribution<int> delayUs(0, 250000);
  int refusedMixes = 0, killed = 0;
  for (int i = 0; i < 40; ++i) {
    const fs::path from = i % 2 ? a : b;
    const pid_t pid = fork();
    if (pid == 0) {
      execl(GALSCULPT_BINARY, GALSCULPT_BINARY, "mesh", "convert", from.c_str(),
            (dir / "out.node").c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(delayUs(rng)));
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    killed += WIFSIGNALED(status);
    const CliRun info = run({"mesh", "info", (dir / "out.node").string()});
    if (info.code == kExitOk) {
      const bool isA =
          info.out.find("vertices: " + std::to_string(verticesA) + "\n") != std::string::npos;
      const bool isB =
          info.out.find("vertices: " + std::to_string(verticesB) + "\n") != std::string::npos;
      EXPECT_TRUE(isA || isB) << info.out;
    } else {
      EXPECT_NE(info.err.find("belongs to another write"), std::string::npos) << info.err;
      ++refusedMixes;
    }
  }
  std::cout << killed << " of 40 writers killed before they finished, " << refusedMixes
            << " mixed sets refused\n";
  EXPECT_GT(killed, 10) << "the kills must land while writing for this test to mean anything";
  // The next write completes the set and leaves no temporary behind.
  ASSERT_EQ(run({"mesh", "convert", a.string(), (dir / "out.node").string()}).code, kExitOk);
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".out."), std::string::npos)
        << e.path() << ": a temporary of a killed writer was left behind";
  EXPECT_EQ(run({"mesh", "info", (dir / "out.node").string()}).code, kExitOk);
}

// The binary, given `seconds` at most: its exit code and standard error, or -1 when it had to be
// killed (it hung).
struct Bounded {
  int code = -1;
  std::string err;
};
Bounded runBinaryWithin(const std::vector<std::string>& args, const fs::path& errFile,
                        double seconds, rlim_t addressLimit = RLIM_INFINITY) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (addressLimit != RLIM_INFINITY) {
      // ulimit -v, and OpenBLAS's threads as a user's environment leaves them.
      const rlimit limit{addressLimit, addressLimit};
      if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(125);
      unsetenv("OPENBLAS_NUM_THREADS");
    }
    std::vector<char*> argv{const_cast<char*>(GALSCULPT_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    if (!freopen(errFile.c_str(), "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(126);
    execv(GALSCULPT_BINARY, argv.data());
    _exit(127);
  }
  Bounded r;
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return r;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -2;
  r.err = test::readText(errFile);
  return r;
}

// Under an address-space limit (ulimit -v) a run ends, and says out of memory when its mesh does
// not fit. Before, OpenBLAS's worker thread spun retrying its buffer and the process hung at exit
// joining it, even after a refusal.
TEST(HostileInput, AnAddressSpaceLimitEndsARunAndSaysWhenItIsTooSmall) {
  test::TempDir dir;
  const Bounded small = runBinaryWithin({"run", (kAssets / "scenes" / "default.json").string(),
                                         "--frames", "2", "--out", (dir / "a").string()},
                                        dir / "err.txt", 60.0, rlim_t(600) << 20);
  EXPECT_EQ(small.code, kExitOk) << small.err;
  const Bounded large =
      runBinaryWithin({"run", (kAssets / "scenes" / "hanging_sphere.json").string(), "--frames",
                       "2", "--out", (dir / "b").string()},
                      dir / "err.txt", 60.0, rlim_t(180) << 20);
  EXPECT_EQ(large.code, 1) << large.err;
  EXPECT_NE(large.err.find("out of memory before starting: simulating"), std::string::npos)
      << large.err;
}

// A disk that fills while a file is written: a file size limit (RLIMIT_FSIZE) makes every
// write past it fail (EFBIG) as a full disk's would (ENOSPC), with no root and no mount needed.
TEST(HostileInput, AFullDiskLeavesNoFileUnderItsFinalNameInAnyFormat) {
  test::TempDir dir;
  const fs::path mesh = kAssets / "meshes" / "sphere_small.node";  // every output > 16 KiB
  for (const std::string ext : {"obj", "stl", "ply", "gltf", "glb", "msh", "vtk", "node"}) {
    const fs::path out = dir / ("out." + ext), err = dir / "err.txt";
    const pid_t pid = fork();
    if (pid == 0) {
      const rlimit limit{16384, 16384};
      if (setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(125);
      if (!freopen(err.c_str(), "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(126);
      execl(GALSCULPT_BINARY, GALSCULPT_BINARY, "mesh", "convert", mesh.c_str(), out.c_str(),
            static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << ext << ": ended by signal " << WTERMSIG(status);
    const std::string message = test::readText(err);
    EXPECT_EQ(WEXITSTATUS(status), kExitOutput) << ext << ": " << message;
    EXPECT_NE(message.find("cannot write"), std::string::npos) << ext << ": " << message;
    EXPECT_NE(message.find("File too large"), std::string::npos)
        << ext << ": the system's error, not a summary: " << message;
    for (const auto& e : fs::directory_iterator(dir.path())) {
      const std::string name = e.path().filename().string();
      EXPECT_TRUE(name == "err.txt") << ext << ": " << name << " left behind";
    }
  }
}

// Two commands given one output folder: the second is refused, naming the first, instead of both
// writing frames into it; when the first dies (kill -9), the folder is free again.
TEST(HostileInput, OneOutputFolderHasOneWriterAtATime) {
  test::TempDir dir;
  const fs::path out = dir / "out", scene = kAssets / "scenes" / "default.json";
  const pid_t first = fork();
  if (first == 0) {
    if (!freopen("/dev/null", "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(126);
    execl(GALSCULPT_BINARY, GALSCULPT_BINARY, "run", scene.c_str(), "--frames", "100000", "--out",
          out.c_str(), "--threads", "1", static_cast<char*>(nullptr));
    _exit(127);
  }
  const fs::path lock = out / FolderLock::kFileName;
  const std::string pid = std::to_string(first);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!(fs::exists(lock) && test::readText(lock) == pid) &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(test::readText(lock), pid) << "the first run holds the folder";
  const CliRun second = run({"run", scene.string(), "--frames", "1", "--out", out.string()});
  EXPECT_EQ(second.code, kExitOutput) << second.err;
  EXPECT_NE(second.err.find("another galsculpt (pid " + pid + ") is writing there"),
            std::string::npos)
      << second.err;
  kill(first, SIGKILL);
  int status = 0;
  waitpid(first, &status, 0);
  const CliRun third = run({"run", scene.string(), "--frames", "1", "--out", out.string()});
  EXPECT_EQ(third.code, kExitOk) << "the lock died with its holder: " << third.err;
  EXPECT_FALSE(fs::exists(lock)) << "a finished writer leaves no lock file";

  // render and open --headless write their pictures under the same rule.
  const FolderLock held(out);
  const fs::path mesh = kAssets / "meshes" / "sphere_small.node";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"render", mesh.string(), "--out", out.string()},
        {"open", mesh.string(), "--headless", "--out", out.string()}}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, kExitOutput) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find("is writing there"), std::string::npos) << args[0] << ": " << r.err;
  }
}

// Ctrl-C or SIGTERM during `run` ends it between two frames, by that signal: metrics.csv keeps
// a whole row for every frame done (it was written only at the end, and lost), and the folder
// holds no temporary and no lock.
TEST(HostileInput, ASignalledRunKeepsItsMetricsRowsAndLeavesNothingElse) {
  test::TempDir dir;
  const fs::path scene = kAssets / "scenes" / "default.json";
  for (const int sig : {SIGTERM, SIGINT}) {
    const fs::path out = dir / ("out" + std::to_string(sig)), err = dir / "err.txt";
    const pid_t pid = fork();
    if (pid == 0) {
      if (!freopen(err.c_str(), "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(126);
      execl(GALSCULPT_BINARY, GALSCULPT_BINARY, "run", scene.c_str(), "--frames", "100000", "--out",
            out.c_str(), "--threads", "1", static_cast<char*>(nullptr));
      _exit(127);
    }
    const fs::path metrics = out / "metrics.csv";
    auto rows = [&] {
      const std::string text = test::readText(metrics);
      return std::count(text.begin(), text.end(), '\n');
    };
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (rows() < 4 && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ASSERT_GE(rows(), 4) << "rows reach the file as frames end";
    kill(pid, sig);
    const auto signalled = std::chrono::steady_clock::now();
    int status = 0;
    waitpid(pid, &status, 0);
    EXPECT_LT(std::chrono::steady_clock::now() - signalled, std::chrono::seconds(10));
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig)
        << "ended by its signal " << sig << ", status " << status;
    const std::string message = test::readText(err);
    EXPECT_NE(message.find("stopped after"), std::string::npos) << message;
    EXPECT_NE(message.find(sig == SIGINT ? "stopped by SIGINT" : "stopped by SIGTERM"),
              std::string::npos)
        << message;
    std::istringstream text(test::readText(metrics));
    std::string header, line;
    ASSERT_TRUE(std::getline(text, header));
    const auto columns = std::count(header.begin(), header.end(), ',');
    int frame = 0;
    while (std::getline(text, line)) {
      EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << "a whole row: " << line;
      EXPECT_EQ(line.substr(0, line.find(',')), std::to_string(++frame)) << line;
    }
    EXPECT_EQ(test::readText(metrics).back(), '\n');
    for (const auto& e : fs::directory_iterator(out))
      EXPECT_EQ(e.path().filename(), "metrics.csv") << e.path() << " left behind";
  }
}

// The pids of a process's children (every thread's).
std::vector<pid_t> childrenOf(pid_t parent) {
  std::vector<pid_t> out;
  std::error_code ec;
  for (const auto& task : fs::directory_iterator("/proc/" + std::to_string(parent) + "/task", ec)) {
    std::ifstream in(task.path() / "children");
    for (pid_t c; in >> c;) out.push_back(c);
  }
  return out;
}

// Whether a process has ended (gone, or a zombie nobody has reaped yet).
bool ended(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(in, line)) return true;
  const size_t close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'Z';
}

// TetGen ran on for 11-13 s after a Ctrl-C or SIGTERM ended `mesh import`, and its temporary
// folder stayed behind; it ends with galsculpt now, and a Ctrl-C or SIGTERM also removes the
// folder and ends galsculpt by that signal (a kill -9 leaves the folder: nothing can run then).
TEST(HostileInput, TetGenEndsWithGalsculpt) {
  test::TempDir dir;
  writeSurface(dir / "ball.obj", makeIcosphere(0.1, 4));
  const fs::path tmp = dir / "tmp";
  fs::create_directory(tmp);
  for (const int sig : {SIGTERM, SIGINT, SIGKILL}) {
    const pid_t pid = fork();
    if (pid == 0) {
      if (!freopen("/dev/null", "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(126);
      setenv("TMPDIR", tmp.c_str(), 1);
      execl(GALSCULPT_BINARY, GALSCULPT_BINARY, "mesh", "import", (dir / "ball.obj").c_str(),
            (dir / "out.node").c_str(), "--tets", "3000000", static_cast<char*>(nullptr));
      _exit(127);
    }
    // Signalled while a TetGen run has been at work for a while (the first, unbounded runs are
    // short).
    pid_t tetgen = 0;
    std::map<pid_t, std::chrono::steady_clock::time_point> seen;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (tetgen == 0 && std::chrono::steady_clock::now() < deadline) {
      const auto now = std::chrono::steady_clock::now();
      for (const pid_t c : childrenOf(pid)) {
        seen.emplace(c, now);
        if (now - seen[c] > std::chrono::milliseconds(500)) tetgen = c;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_NE(tetgen, 0) << "no TetGen run lasted half a second";
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig)
        << "galsculpt ended by its signal " << sig << ", status " << status;
    if (sig != SIGKILL) {
      for (const auto& e : fs::directory_iterator(tmp))
        ADD_FAILURE() << e.path() << " left behind after signal " << sig;
    }
    const auto gone = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (!ended(tetgen) && std::chrono::steady_clock::now() < gone)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_TRUE(ended(tetgen)) << "TetGen (pid " << tetgen << ") outlived galsculpt's signal "
                               << sig;
    if (!ended(tetgen)) kill(tetgen, SIGKILL);
  }
}

TEST(HostileInput, SpecialFilesAreRefusedBeforeAnythingWaitsOnThem) {
  // A named pipe with no writer blocks whoever opens it for reading; `render` and `open` did.
  test::TempDir dir;
  const std::vector<std::string> names = {"pipe",      "pipe.json",   "pipe.obj",
                                          "pipe.node", "pipe.gsproj", "pipe.stl"};
  for (const std::string& name : names) ASSERT_EQ(mkfifo((dir / name).c_str(), 0600), 0) << name;
  fs::create_symlink(dir / "loop_b.obj", dir / "loop_a.obj");
  fs::create_symlink(dir / "loop_a.obj", dir / "loop_b.obj");
  const fs::path out = dir / "out", err = dir / "err.txt";
  struct Case {
    std::string file, says;
  };
  std::vector<Case> cases;
  for (const std::string& name : names)
    cases.push_back({name, (name == "pipe" ? "pipe.node" : name) + ": is a named pipe (FIFO)"});
  cases.push_back({"loop_a.obj", "loop_a.obj: is a loop of symbolic links"});
  for (const Case& c : cases) {
    const std::string file = (dir / c.file).string();
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"render", file, "--out", out.string()},
          {"open", file, "--headless", "--out", out.string()},
          {"mesh", "info", file},
          {"run", file, "--frames", "1", "--out", out.string()},
          {"scene", "check", file}}) {
      const Bounded r = runBinaryWithin(args, err, 20.0);
      ASSERT_NE(r.code, -1) << args[0] << " " << c.file << ": hung on a special file";
      EXPECT_EQ(r.code, kExitBadInput) << args[0] << " " << c.file << ": " << r.err;
      // What names the file's kind where the command reads it as what it is; the rest refuse
      // it by its name (a scene check or `run` on a mesh name).
      if (args[0] == "render" || args[0] == "open") {
        EXPECT_NE(r.err.find(c.says), std::string::npos) << args[0] << ": " << r.err;
      }
    }
  }
}

}  // namespace
}  // namespace galsculpt
