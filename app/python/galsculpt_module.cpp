// The Python module `galsculpt` (docs/python.md): the engine's own session driven from Python.
// Arrays view the engine's memory (read-only, kept alive by the Simulation object); a step runs
// without the GIL. Errors become ValueError (bad content: the reader's message, file and JSON
// path) or OSError (files).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <signal.h>
#include <unistd.h>

#include "app/cli/bench.h"
#include "app/cli/cli.h"
#include "app/cli/cli_args.h"
#include "app/cli/run_command.h"
#include "engine/scene/solver_options_json.h"
#include "engine/session/project_file.h"
#include "engine/session/session_loader.h"
#include "engine/surface/surface_io.h"
#include "solver/frame/parallel.h"
#include "solver/io/input_error.h"
#include "solver/io/memory_limits.h"
#include "solver/io/stop_request.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace galsculpt {
namespace {

// Raises a Python exception of `type`.
[[noreturn]] void raise(PyObject* type, const std::string& message) {
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

// A path argument: str or os.PathLike (pathlib.Path), never empty or with an embedded NUL (which
// the file system would cut the name at, writing another file than asked).
std::string pathArgument(const py::object& path, const char* what) {
  const py::object text = py::module_::import("os").attr("fspath")(path);
  if (!py::isinstance<py::str>(text))
    throw py::type_error(std::string(what) + ": a str or os.PathLike path, not bytes");
  const std::string s = text.cast<std::string>();
  if (s.empty()) throw py::value_error(std::string(what) + ": an empty path");
  if (s.find('\0') != std::string::npos)
    throw py::value_error(std::string(what) + ": the path holds a NUL character");
  return s;
}

// Python values through JSON: the readers' own format, so that they validate what Python gives.
// A number JSON cannot hold (NaN, inf) is a ValueError naming where it is (`where`: "event",
// then ".radius", "[1]", ...), as the readers name a key, not the JSON library's parse error.
void checkFinite(const py::handle& value, const std::string& where) {
  if (py::isinstance<py::float_>(value)) {
    if (!std::isfinite(value.cast<double>()))
      throw py::value_error(where + ": " + py::repr(value).cast<std::string>() +
                            " is not a finite number");
  } else if (py::isinstance<py::dict>(value)) {
    for (const auto& [key, item] : value.cast<py::dict>())
      checkFinite(item, where + "." + py::str(key).cast<std::string>());
  } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    int i = 0;
    for (const py::handle& item : value) checkFinite(item, where + "[" + std::to_string(i++) + "]");
  }
}

nlohmann::json toJson(const py::handle& value, const std::string& where) {
  checkFinite(value, where);
  const std::string text = py::module_::import("json").attr("dumps")(value).cast<std::string>();
  return nlohmann::json::parse(text);
}
py::object fromJson(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

// A frame's figures by their metrics columns (engine/session/simulation.h: the same names as
// the CSV's).
py::dict metricsDict(const FrameMetrics& m) {
  py::dict d;
  for (const MetricsColumn& c : metricsColumns())
    std::visit([&](auto field) { d[c.name] = m.*field; }, c.field);
  return d;
}

// A read-only array over memory `owner` keeps alive.
template <typename T>
py::array view(const T* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
               const py::handle& owner) {
  py::array_t<T> a(std::move(shape), std::move(strides), data, owner);
  reinterpret_cast<py::detail::PyArray_Proxy*>(a.ptr())->flags &=
      ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::array vec3View(const std::vector<Vec3>& v, const py::handle& owner) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  return view(v.empty() ? nullptr : v.front().data(), {static_cast<py::ssize_t>(v.size()), 3},
              {sizeof(Vec3), sizeof(double)}, owner);
}

class PySimulation {
 public:
  // `source`: a path (str or os.PathLike) of anything `galsculpt open` opens, or a scene as a
  // dict (the JSON object of docs/scenes.md; relative paths from the working directory).
  PySimulation(const py::object& source, const py::object& solverOptions) {
    SolverOverrides overrides;
    if (!solverOptions.is_none())
      for (const auto& [key, value] : solverOptions.cast<py::dict>())
        overrides.emplace_back(py::str(key).cast<std::string>(),
                               toJson(value, "solver_options." + py::str(key).cast<std::string>()));
    if (py::isinstance<py::dict>(source)) {
      const SceneDescription scene = withSolverOverrides(
          parseScene(toJson(source, "scene"), fs::current_path() / "<dict>"), overrides);
      session_ = std::make_unique<SculptSession>(scene, loadSceneMesh(scene));
      return;
    }
    const std::string path = pathArgument(source, "path");
    if (!fs::exists(path)) raise(PyExc_FileNotFoundError, path + ": no such file");
    OpenedSession opened = openSession(path, {}, 20000, overrides);
    session_ = std::move(opened.session);
  }

  py::dict step(int frames) {
    if (frames < 1)
      throw py::value_error("frames must be at least 1, got " + std::to_string(frames));
    FrameMetrics m;
    std::vector<std::string> idle;
    bool interrupted = false;
    {
      py::gil_scoped_release released;
      std::lock_guard<std::mutex> lock(busy_);
      for (int f = 0; f < frames && !interrupted; ++f) {
        m = session_->step();
        for (std::string& report : session_->takeIdleReports()) idle.push_back(std::move(report));
        // Ctrl-C between frames: KeyboardInterrupt after the frame under way, whole.
        py::gil_scoped_acquire acquired;
        interrupted = PyErr_CheckSignals() != 0;
      }
    }
    if (interrupted) throw py::error_already_set();
    // Applied events that acted on nothing: Python warnings, and listed with the figures.
    py::dict figures = metricsDict(m);
    py::list warned;
    for (const std::string& report : idle) {
      if (PyErr_WarnEx(PyExc_UserWarning, report.c_str(), 1) < 0) throw py::error_already_set();
      warned.append(report);
    }
    figures["tool_warnings"] = warned;
    return figures;
  }

  void apply(const py::dict& event) {
    Guard guard(*this);
    nlohmann::json e = toJson(event, "event");
    const int frame = session_->simulation().frame();
    if (!e.is_object()) throw py::value_error("an event is a dict");
    if (!e.contains("frame")) e["frame"] = frame;
    if (e["frame"] != frame)
      throw py::value_error(
          "event.frame: an applied event acts from the next step: leave it out "
          "or give the current frame (" +
          std::to_string(frame) + ")");
    session_->apply(parseToolEvent(e, "event", "<python>"), "<python>");
  }

  bool undo() {
    Guard guard(*this);
    return session_->undo();
  }
  bool redo() {
    Guard guard(*this);
    return session_->redo();
  }

  void reset() {
    Guard guard(*this);
    session_->reset();
  }

  int frame() {
    Guard guard(*this);
    return session_->simulation().frame();
  }
  double time() {
    Guard guard(*this);
    return session_->simulation().state().time;
  }
  int pieces() {
    Guard guard(*this);
    return session_->simulation().pieceStats().pieces;
  }

  py::tuple surface() {
    Guard guard(*this);
    const Simulation& sim = session_->simulation();
    const VisualSurface& s = sim.surface();
    const auto faces = static_cast<py::ssize_t>(s.mesh.faces.size());
    py::array_t<double> vertices(
        {static_cast<py::ssize_t>(s.mesh.vertices.size()), py::ssize_t(3)});
    py::array_t<int> triangles({faces, py::ssize_t(3)});
    py::array_t<int> piece(faces);
    auto v = vertices.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < v.shape(0); ++i)
      for (int k = 0; k < 3; ++k) v(i, k) = s.mesh.vertices[i][k];
    auto t = triangles.mutable_unchecked<2>();
    auto p = piece.mutable_unchecked<1>();
    for (py::ssize_t f = 0; f < faces; ++f) {
      for (int k = 0; k < 3; ++k) t(f, k) = s.mesh.faces[f][k];
      p(f) = sim.pieceOf(s.cellVertex[f]);
    }
    return py::make_tuple(vertices, triangles, piece);
  }

  void exportSurface(const py::object& where) {
    const std::string path = pathArgument(where, "path");
    Guard guard(*this);
    writeVisualSurface(path, session_->simulation().exportSurface().surface);
  }
  int exportTets(const py::object& where) {
    const std::string path = pathArgument(where, "path");
    if (fs::path(path).filename().empty() || fs::path(path).stem().empty())
      throw py::value_error("path: names no file (" + path + ")");
    Guard guard(*this);
    fs::path stem = path;
    if (stem.extension() == ".node") stem.replace_extension();
    return session_->simulation().writeTetsWithDamage(stem);
  }
  void saveProject(const py::object& where) {
    const std::string path = pathArgument(where, "path");
    Guard guard(*this);
    writeProject(path, *session_, std::nullopt);
  }

  py::object options() {
    Guard guard(*this);
    return fromJson(solverOptionsJson(session_->scene().solver));
  }

  // The arrays: views of the engine's memory, valid while the simulation lives.
  static py::array positions(const py::object& self) { return vec3View(state(self).x, self); }
  static py::array velocities(const py::object& self) { return vec3View(state(self).v, self); }
  // Setters (MuJoCo's qpos / qvel): an undoable action of the session, not a tool event.
  static void setPositions(const py::object& self, const py::object& values) {
    std::vector<Vec3> x = rowsOfThree(values, "positions");
    PySimulation& s = self.cast<PySimulation&>();
    Guard guard(s);
    s.session_->setState(&x, nullptr);
  }
  static void setVelocities(const py::object& self, const py::object& values) {
    std::vector<Vec3> v = rowsOfThree(values, "velocities");
    PySimulation& s = self.cast<PySimulation&>();
    Guard guard(s);
    s.session_->setState(nullptr, &v);
  }
  static py::array restPositions(const py::object& self) {
    return vec3View(self.cast<PySimulation&>().sim().model().mesh.vertices, self);
  }
  static py::array tets(const py::object& self) {
    const std::vector<Tet>& t = self.cast<PySimulation&>().sim().model().mesh.tets;
    static_assert(sizeof(Tet) == 4 * sizeof(int));
    return view(t.empty() ? nullptr : t.front().data(), {static_cast<py::ssize_t>(t.size()), 4},
                {sizeof(Tet), sizeof(int)}, self);
  }
  static py::array edges(const py::object& self) {
    const std::vector<Edge>& e = self.cast<PySimulation&>().sim().model().edges;
    static_assert(sizeof(Edge) == 2 * sizeof(int));
    return view(e.empty() ? nullptr : e.front().data(), {static_cast<py::ssize_t>(e.size()), 2},
                {sizeof(Edge), sizeof(int)}, self);
  }
  static py::array damage(const py::object& self) {
    const std::vector<std::uint8_t>& d = state(self).damaged;
    return view(d.data(), {static_cast<py::ssize_t>(d.size())}, {1}, self);
  }

 private:
  // Every call but step takes the simulation while no step runs in another thread.
  struct Guard {
    std::unique_lock<std::mutex> lock;
    explicit Guard(PySimulation& s) : lock(s.busy_, std::try_to_lock) {
      if (!lock.owns_lock())
        throw std::runtime_error("the simulation is stepping in another thread");
    }
  };
  const Simulation& sim() {
    Guard guard(*this);
    return session_->simulation();
  }
  // An (n, 3) array of numbers as rows; ValueError naming `what` for another shape.
  static std::vector<Vec3> rowsOfThree(const py::object& values, const std::string& what) {
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
    if (!a || a.ndim() != 2 || a.shape(1) != 3)
      throw py::value_error(what + ": expected an (n, 3) array of numbers");
    std::vector<Vec3> rows(static_cast<size_t>(a.shape(0)));
    const auto r = a.unchecked<2>();
    for (py::ssize_t i = 0; i < a.shape(0); ++i) rows[i] = Vec3(r(i, 0), r(i, 1), r(i, 2));
    return rows;
  }
  static const SimState& state(const py::object& self) {
    return self.cast<PySimulation&>().sim().state();
  }

  std::unique_ptr<SculptSession> session_;
  std::mutex busy_;
};

// The command's poll of Python's signals: SIGINT when a KeyboardInterrupt is pending (left set,
// raised once the command returns).
int pythonStopPoll() {
  py::gil_scoped_acquire acquired;
  return PyErr_CheckSignals() != 0 ? SIGINT : 0;
}

// A usage message as Python names the keyword: `--export-every` is `export_every`.
std::string pythonKeywords(const std::string& message) {
  std::string text;
  for (size_t i = 0; i < message.size(); ++i) {
    const bool flag = message.compare(i, 2, "--") == 0 && i + 2 < message.size() &&
                      std::islower(static_cast<unsigned char>(message[i + 2])) &&
                      (i == 0 || !std::isalnum(static_cast<unsigned char>(message[i - 1])));
    if (!flag) {
      text.push_back(message[i]);
      continue;
    }
    for (i += 2; i < message.size() &&
                 (std::isalnum(static_cast<unsigned char>(message[i])) || message[i] == '-');
         ++i)
      text.push_back(message[i] == '-' ? '_' : message[i]);
    --i;
  }
  return text;
}

// A command's work (play, bench) in this process without the GIL, with `threads` CPU threads for
// its time when given. Ctrl-C reaches its loops, which stop as on the command line (between
// frames or Newton iterations, outputs whole) and raise KeyboardInterrupt; a usage error is a
// ValueError naming the keyword; other errors as the module's translator maps them.
template <typename Work>
auto runCommandWork(const std::optional<int>& threads, Work&& work) {
  if (threads && (*threads < 1 || *threads > 1024))
    throw py::value_error("threads expects an integer in [1, 1024], got " +
                          std::to_string(*threads));
  struct Restore {
    int threads = threadCount();
    ~Restore() {
      setStopPoller(nullptr);
      clearStopRequest();
      setThreadCount(threads);
    }
  } restore;
  if (threads) setThreadCount(*threads);
  setStopPoller(pythonStopPoll);
  try {
    py::gil_scoped_release released;
    return work();
  } catch (const Interrupted& e) {
    if (PyErr_Occurred()) throw py::error_already_set();
    raise(PyExc_KeyboardInterrupt, e.what());
  } catch (const UsageError& e) {
    throw py::value_error(pythonKeywords(e.what()));
  }
}

// solver_option (a dict of the scene's solver keys) and backend, as --solver-option and
// --backend give them: the backend wins.
SolverOverrides commandSolverOverrides(const py::object& solverOption,
                                       const std::optional<std::string>& backend) {
  SolverOverrides overrides;
  if (!solverOption.is_none()) {
    if (!py::isinstance<py::dict>(solverOption))
      throw py::type_error("solver_option: a dict of the scene's solver keys");
    for (const auto& [key, value] : solverOption.cast<py::dict>())
      overrides.emplace_back(py::str(key).cast<std::string>(),
                             toJson(value, "solver_option." + py::str(key).cast<std::string>()));
  }
  if (backend) {
    if (!enumFromName<BackendRequest>(*backend))
      throw py::value_error("backend must be auto, cpu, cuda or device-like, got '" + *backend + "'");
    overrides.emplace_back("backend", *backend);
  }
  return overrides;
}

// What a command said on standard error, as lists: its warnings and notes (without the prefix).
void addMessages(py::dict& result, const std::string& said) {
  py::list warnings, notes;
  std::istringstream lines(said);
  for (std::string line; std::getline(lines, line);) {
    const size_t cr = line.rfind('\r');  // a progress bar's redraw before it
    if (cr != std::string::npos) line = line.substr(cr + 1);
    if (line.rfind("\x1b[K", 0) == 0) line = line.substr(3);
    if (line.rfind("warning: ", 0) == 0) warnings.append(line.substr(9));
    if (line.rfind("note: ", 0) == 0) notes.append(line.substr(6));
  }
  result["warnings"] = warnings;
  result["notes"] = notes;
}

py::dict play(const py::object& scriptPath, const py::object& outPath, const py::object& metrics,
              int exportEvery, const std::string& exportFormat, bool exportTets, int pngEvery,
              std::pair<int, int> size, const std::string& solver, const py::object& solverOption,
              const std::optional<std::string>& backend, const std::optional<int>& threads) {
  const std::string script = pathArgument(scriptPath, "script");
  if (!fs::exists(script)) raise(PyExc_FileNotFoundError, script + ": no such file");
  RunOptions o;
  o.outDir = pathArgument(outPath, "out");
  if (!metrics.is_none()) o.metricsPath = pathArgument(metrics, "metrics");
  o.exportEvery = exportEvery;
  o.exportFormat = exportFormat;
  o.exportTets = exportTets;
  o.pngEvery = pngEvery;
  std::tie(o.width, o.height) = size;
  if (solver != "scene" && solver != "reference")
    throw py::value_error("solver must be 'scene' or 'reference', got '" + solver + "'");
  o.solver = solver == "reference" ? SolverChoice::Reference : SolverChoice::FromScene;
  const SolverOverrides overrides = commandSolverOverrides(solverOption, backend);
  std::ostringstream out, err;
  std::vector<FrameMetrics> frames;
  const RunSummary summary = runCommandWork(threads, [&] {
    return playScript(script, o, overrides, out, err,
                      [&frames](const FrameMetrics& m) { frames.push_back(m); });
  });
  py::dict result;
  result["output"] = out.str();
  py::list rows;
  for (const FrameMetrics& m : frames) rows.append(metricsDict(m));
  result["metrics"] = rows;
  result["final_surface"] = summary.finalSurface.string();
  result["metrics_file"] = summary.metricsPath.string();
  py::list files;
  for (const std::string& name : summary.written) files.append(name);
  result["files"] = files;
  addMessages(result, err.str());
  return result;
}

py::dict bench(const std::vector<std::string>& scenes, int frames, bool quick,
               const std::optional<std::string>& preset, bool sweep, bool cracks,
               const std::vector<int>& settle, const std::optional<std::string>& debris,
               const py::object& referenceDir, const py::object& json,
               const py::object& solverOption, const std::optional<std::string>& backend,
               const std::optional<int>& threads) {
  BenchOptions o;
  o.scenes = scenes;
  o.frames = frames;
  o.quick = quick;
  o.sweep = sweep;
  o.cracks = cracks;
  o.settles = settle;
  if (preset && !preset->empty()) {
    o.preset = enumFromName<SolverPreset>(*preset);
    if (!o.preset)
      throw py::value_error("preset must be converged or paper, got '" + *preset + "'");
  }
  if (debris) {
    o.debris = debrisRuleFromName(*debris);
    if (!o.debris) throw py::value_error("debris must be keep or remove, got '" + *debris + "'");
  }
  if (!referenceDir.is_none()) o.referenceDir = pathArgument(referenceDir, "reference_dir");
  if (!json.is_none()) o.json = pathArgument(json, "json");
  o.solver = commandSolverOverrides(solverOption, backend);
  std::ostringstream out, err;
  const nlohmann::json doc = runCommandWork(threads, [&] { return runBench(o, out, err); });
  py::dict result = fromJson(doc).cast<py::dict>();
  result["output"] = out.str();
  addMessages(result, err.str());
  return result;
}

}  // namespace
}  // namespace galsculpt

PYBIND11_MODULE(galsculpt, m) {
  using namespace galsculpt;
  m.doc() = "Galsculpt: graph-based FEM sculpting and fracture (docs/python.md)";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const OutputError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const fs::filesystem_error& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const OutOfMemory& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    }
  });

  m.attr("__version__") = GALSCULPT_VERSION;
  py::class_<PySimulation>(m, "Simulation",
                           "A sculpting session: a scene, project, playback script or mesh, "
                           "stepped from Python (docs/python.md). Arrays are read-only views of "
                           "the engine's memory, valid while the Simulation lives.")
      .def(py::init<const py::object&, const py::object&>(), py::arg("source"),
           py::arg("solver_options") = py::none(),
           "source: a path (str or os.PathLike) of a scene (.json), a playback script "
           "(replayed), a project (.gsproj) or a mesh; or a scene as a dict (relative paths from "
           "the working directory). solver_options: solver keys over the scene's "
           "(docs/scenes.md). FileNotFoundError for a missing file, ValueError naming the file "
           "and key for bad content.")
      .def("step", &PySimulation::step, py::arg("frames") = 1,
           "Runs frames; returns the last one's figures (the metrics CSV's columns) and "
           "tool_warnings: the applied events that acted on nothing (also UserWarnings)")
      .def("apply", &PySimulation::apply, py::arg("event"),
           "A playback script's event (docs/scripts.md) as a dict, acting from the next step; "
           "checked as a script's are (ValueError naming the key)")
      .def("undo", &PySimulation::undo, "Undoes the last action (a step, an event); False if none")
      .def("redo", &PySimulation::redo, "Redoes what undo took back; False if nothing")
      .def("reset", &PySimulation::reset,
           "Back to the state it was opened in, forgetting the recording (undo brings it back)")
      .def_property_readonly("frame", &PySimulation::frame, "Frames stepped so far")
      .def_property_readonly("time", &PySimulation::time, "Simulated time in s")
      .def_property_readonly("pieces", &PySimulation::pieces,
                             "Pieces the body is in (connected through undamaged edges)")
      .def_property_readonly("options", &PySimulation::options,
                             "The solver options as the scene's \"solver\" object holds them")
      .def_property("positions", &PySimulation::positions, &PySimulation::setPositions,
                    "Current vertex positions (n, 3), m: a read-only view; assign an (n, 3) "
                    "array to set them (an undoable action, not recorded as a tool)")
      .def_property("velocities", &PySimulation::velocities, &PySimulation::setVelocities,
                    "Current vertex velocities (n, 3), m/s: a read-only view; assign an (n, 3) "
                    "array to set them (an undoable action, not recorded as a tool)")
      .def_property_readonly("rest_positions", &PySimulation::restPositions,
                             "Rest vertex positions (n, 3), m")
      .def_property_readonly("tets", &PySimulation::tets, "Tets' vertices (t, 4), int32")
      .def_property_readonly("edges", &PySimulation::edges,
                             "The mesh's edges (e, 2), int32, sorted: damage[i] is edges[i]'s")
      .def_property_readonly("damage", &PySimulation::damage,
                             "Per edge of `edges`: 1 damaged for good, 0 intact (uint8)")
      .def("surface", &PySimulation::surface,
           "The visualization surface: (vertices (k, 3), triangles (t, 3), piece of each "
           "triangle (t,))")
      .def("export", &PySimulation::exportSurface, py::arg("path"),
           "Writes the export surface (one closed shell per piece, docs/surface.md) by "
           "extension: obj, ply, stl, gltf, glb")
      .def("export_tets", &PySimulation::exportTets, py::arg("path"),
           "Writes the tet mesh at the current positions with its damage (stem.node/.ele/.face, "
           ".damage, .vtk); returns how many tets parted and crushed flat were left out")
      .def("save_project", &PySimulation::saveProject, py::arg("path"),
           "Saves the session as a project (.gsproj) that reopens to the same bits");

  m.def("play", &play, py::arg("script"), py::arg("out"), py::kw_only(),
        py::arg("metrics") = py::none(), py::arg("export_every") = 0,
        py::arg("export_format") = "obj", py::arg("export_tets") = false, py::arg("png_every") = 0,
        py::arg("size") = std::pair<int, int>{1280, 800}, py::arg("solver") = "scene",
        py::arg("solver_option") = py::none(), py::arg("backend") = py::none(),
        py::arg("threads") = py::none(),
        "`galsculpt play SCRIPT --out OUT`, in this process: the script's frames with their "
        "outputs in `out`. Keywords are play's flags (docs/cli.md): metrics (default "
        "out/metrics.csv), export_every, export_format, export_tets, png_every, size (w, h), "
        "solver ('scene' or 'reference'), solver_option (a dict of solver keys), backend, "
        "threads (for this call). Returns {output: what it prints, metrics: each frame's row "
        "as a dict, final_surface, metrics_file, files: the names written in out, warnings, "
        "notes}. FileNotFoundError for a missing script, ValueError naming the key");
  m.def("bench", &bench, py::arg("scenes") = std::vector<std::string>{}, py::arg("frames") = 0,
        py::arg("quick") = false, py::arg("preset") = py::none(), py::kw_only(),
        py::arg("sweep") = false, py::arg("cracks") = false,
        py::arg("settle") = std::vector<int>{0}, py::arg("debris") = py::none(),
        py::arg("reference_dir") = py::none(), py::arg("json") = py::none(),
        py::arg("solver_option") = py::none(), py::arg("backend") = py::none(),
        py::arg("threads") = py::none(),
        "`galsculpt bench`, in this process: speed against error. scenes: names (default all; "
        "quick's pair; cracks's sphere); frames (0: 60, 20 with quick); preset ('converged' or "
        "'paper'); sweep, cracks, settle (window starts), debris ('keep' or 'remove'), "
        "reference_dir, json (also written there), solver_option, backend, threads as bench's "
        "flags (docs/cli.md). Returns its JSON document (machine, frames, settle_frames, "
        "settle_windows, results) with output (what it prints), warnings and notes");
}
