"""The Python module (app/python/galsculpt_module.cpp, docs/python.md): every entry of its
contract, the arrays as views of the engine's memory, errors as exceptions with the readers'
messages, the GIL released during a step, and a script played from Python as `galsculpt play`
plays it."""
import json
import os
import pathlib
import subprocess
import threading
import time

import numpy as np
import pytest

import galsculpt

SOURCE = pathlib.Path(__file__).resolve().parents[3]
BALL = str(SOURCE / "assets" / "scenes" / "default.json")
SCRIPT = str(SOURCE / "assets" / "scripts" / "sphere_cut.json")
# A horizontal blade swept down through the clay ball: two pieces.
KNIFE = {"tool": "knife", "from": [[-0.2, 0.2, 0.02], [0.2, 0.2, 0.02]],
         "to": [[-0.2, -0.2, 0.02], [0.2, -0.2, 0.02]]}


@pytest.fixture(scope="module")
def ball():
    return galsculpt.Simulation(BALL)


def test_step_returns_the_frames_figures(ball):
    start = ball.frame
    report = ball.step(2)
    assert ball.frame == start + 2
    for key in ("residual", "converged", "newton_iterations", "cg_iterations", "ms_total"):
        assert key in report
    assert isinstance(report["converged"], bool)
    assert isinstance(report["newton_iterations"], int)
    assert report["ms_total"] > 0.0
    assert report["frame"] == ball.frame
    with pytest.raises(ValueError, match="frames must be at least 1"):
        ball.step(0)


def test_arrays_view_the_engines_memory_read_only(ball):
    x = ball.positions
    assert x.shape == (ball.rest_positions.shape[0], 3) and x.dtype == np.float64
    assert ball.velocities.shape == x.shape
    tets = ball.tets
    assert tets.dtype == np.int32 and tets.shape[1] == 4
    assert tets.max() == x.shape[0] - 1
    assert ball.damage.dtype == np.uint8
    for array in (x, ball.velocities, ball.rest_positions, tets, ball.damage):
        assert not array.flags.writeable
        assert not array.flags.owndata, "a view, not a copy"
    with pytest.raises(ValueError):
        x[0, 0] = 1.0
    # The same memory every time, and it moves with the simulation.
    assert ball.positions.__array_interface__["data"][0] == x.__array_interface__["data"][0]
    before = x.copy()
    ball.apply({"tool": "brush", "center": x[0].tolist(), "radius": 0.05,
                "offset": [0.0, 0.03, 0.0], "duration": 3})
    ball.step(3)
    assert not np.array_equal(before, x), "the view shows the new positions"


def test_positions_and_velocities_are_set_as_an_undoable_action():
    sim = galsculpt.Simulation(BALL)
    sim.step()
    view = sim.positions
    lifted = sim.positions + np.array([0.0, 0.05, 0.0])
    sim.positions = lifted
    assert np.array_equal(sim.positions, lifted)
    assert view.__array_interface__["data"][0] == sim.positions.__array_interface__["data"][0], \
        "views taken before stay views"
    sim.velocities = np.zeros_like(lifted) + [0.0, 0.0, 0.2]
    assert np.all(sim.velocities[:, 2] == 0.2)
    report = sim.step()
    assert report["converged"]
    sim.undo()  # the step
    sim.undo()  # the velocities
    sim.undo()  # the positions
    assert not np.array_equal(sim.positions, lifted)
    assert np.all(sim.velocities[:, 2] != 0.2)
    before = sim.positions.copy()
    with pytest.raises(ValueError, match=r"positions: expected an \(n, 3\) array"):
        sim.positions = np.zeros((5, 2))
    with pytest.raises(ValueError, match="positions: 5 rows for a model of"):
        sim.positions = np.zeros((5, 3))
    bad = before.copy()
    bad[3, 1] = np.inf
    with pytest.raises(ValueError, match=r"positions\[3\]: not a finite number"):
        sim.positions = bad
    with pytest.raises(ValueError, match="velocities: expected"):
        sim.velocities = "fast"
    assert np.array_equal(sim.positions, before), "a refused value changes nothing"


def test_a_scenes_initial_velocity_throws_the_body(tmp_path):
    scene = {"mesh": {"file": str(SOURCE / "assets" / "meshes" / "sphere_small.node")},
             "material": {"preset": "rubber"}, "gravity": [0, 0, 0],
             "initial_velocity": {"linear": [0.3, 0, 0]}}
    sim = galsculpt.Simulation(scene)
    assert np.allclose(sim.velocities, [0.3, 0, 0])
    sim.step(6)
    assert abs(np.mean(sim.positions - sim.rest_positions, axis=0)[0] - 0.03) < 1e-3
    sim.reset()
    assert np.allclose(sim.velocities, [0.3, 0, 0]), "reset goes back to the scene's start"


def test_apply_undo_redo_and_the_pieces():
    sim = galsculpt.Simulation(BALL)
    sim.step()
    assert sim.pieces == 1
    sim.apply(KNIFE)
    assert int(sim.damage.sum()) == 0, "an event acts from the next step"
    sim.step()
    cut = int(sim.damage.sum())
    assert cut > 0
    assert sim.pieces == 2
    assert sim.undo()
    assert int(sim.damage.sum()) == 0 and sim.frame == 1
    assert sim.redo()
    assert int(sim.damage.sum()) == cut and sim.frame == 2
    vertices, triangles, piece = sim.surface()
    assert vertices.shape[1] == 3 and triangles.shape[1] == 3
    assert triangles.dtype == np.int32 and piece.shape == (triangles.shape[0],)
    assert set(np.unique(piece)) == {0, 1}
    assert triangles.max() < vertices.shape[0]


def test_bad_events_name_their_key(ball):
    with pytest.raises(ValueError, match=r"event\.tool"):
        ball.apply({"tool": "chisel"})
    with pytest.raises(ValueError, match="radius"):
        ball.apply({"tool": "brush", "center": [0, 0, 0], "radius": -1, "offset": [0, 0, 0]})
    with pytest.raises(ValueError, match="acts from the next step"):
        ball.apply(dict(KNIFE, frame=ball.frame + 5))


def test_applied_events_are_checked_against_the_mesh_and_scene_as_a_scripts_are():
    # Each of these crashed a later step (a seed past the vertices read out of bounds) or made
    # every later step fail; apply() refuses them as `play` refuses them in a script, records
    # nothing, and the session steps on.
    sim = galsculpt.Simulation(BALL)
    vertices = sim.rest_positions.shape[0]
    bad = [
        ({"tool": "push", "center": [0, 0, 0.1], "radius": 0.05, "seed": 10**9},
         r"event\.seed: 1000000000 is not a vertex of the mesh"),
        ({"tool": "grab", "center": [0, 0, 0.1], "radius": 0.05, "seed": vertices},
         r"event\.seed: %d is not a vertex" % vertices),
        ({"tool": "anchor_paint", "center": [0, 0, 0.1], "radius": 0.05, "seed": 10**9},
         r"event\.seed"),
        ({"tool": "anchor", "anchor": {"vertices": [10**8]}}, r"event\.anchor"),
        ({"tool": "anchor", "action": "remove", "scene_anchor": 99},
         r"event\.scene_anchor: the scene has 1 anchor"),
        ({"tool": "anchor", "action": "remove", "name": "nobody"},
         r"event\.name: no anchor named \"nobody\""),
    ]
    for event, message in bad:
        with pytest.raises(ValueError, match="<python>: " + message):
            sim.apply(event)
    assert sim.undo() is False, "nothing was recorded"
    assert sim.step()["converged"]
    # An anchor added by an event still to act may be removed after it.
    sim.apply({"tool": "anchor", "name": "a", "anchor": {"vertices": [0]}})
    sim.apply({"tool": "anchor", "action": "remove", "name": "a"})
    sim.step()


def test_ctrl_c_stops_a_long_step_and_play_between_frames(tmp_path):
    import signal
    sim = galsculpt.Simulation(BALL)
    threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        sim.step(100000)
    assert time.monotonic() - started < 10.0
    assert 0 < sim.frame < 100000, "stopped after a whole frame"
    sim.step()  # and steps on
    threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    with pytest.raises(KeyboardInterrupt):
        galsculpt.play(SCRIPT, tmp_path / "o", solver_option={"newton_iters": 40})
    # The stop is not left behind for the next command.
    played = galsculpt.play(SCRIPT, tmp_path / "p")
    assert played["metrics"][-1]["frame"] == 120


def test_an_event_that_acts_on_nothing_is_a_warning():
    sim = galsculpt.Simulation(BALL)
    sim.apply({"tool": "knife", "duration": 1, "from": [[-0.2, 0.5, 0], [0.2, 0.5, 0]],
               "to": [[-0.2, 0.4, 0], [0.2, 0.4, 0]]})
    with pytest.warns(UserWarning, match=r"frame 0: knife \(\$\.events\[0\]\) crossed no edge"):
        report = sim.step()
    assert len(report["tool_warnings"]) == 1
    sim.apply(KNIFE)
    assert sim.step()["tool_warnings"] == [], "a knife through the ball cuts"


def test_paths_dict_scenes_time_edges_reset_and_the_version(tmp_path):
    assert isinstance(galsculpt.__version__, str) and galsculpt.__version__.count(".") >= 1
    for documented in (galsculpt.Simulation, galsculpt.Simulation.step, galsculpt.Simulation.reset,
                       galsculpt.Simulation.edges, galsculpt.Simulation.time, galsculpt.play,
                       galsculpt.bench):
        assert documented.__doc__, documented
    sim = galsculpt.Simulation(pathlib.Path(BALL))
    sim.step(3)
    assert sim.time == pytest.approx(3 * 0.0166667, rel=1e-6)
    edges = sim.edges
    assert edges.dtype == np.int32 and edges.shape == (sim.damage.shape[0], 2)
    assert (edges[:, 0] < edges[:, 1]).all() and edges.max() == sim.positions.shape[0] - 1
    assert not edges.flags.writeable
    # Every damaged edge's ends are in different pieces after a clean cut through the ball.
    sim.apply(KNIFE)
    sim.step()
    assert sim.damage.sum() > 0
    sim.reset()
    assert sim.frame == 0 and sim.time == 0.0 and sim.damage.sum() == 0
    assert sim.undo(), "the reset is undoable"
    assert sim.frame == 4
    # A scene as a dict, paths from the working directory.
    scene = json.loads(pathlib.Path(BALL).read_text())
    scene["mesh"]["file"] = str(SOURCE / "assets" / "meshes" / "sphere_small.node")
    from_dict = galsculpt.Simulation(scene)
    assert from_dict.positions.shape == sim.positions.shape
    with pytest.raises(ValueError, match=r"\$\.material\.preset"):
        galsculpt.Simulation(dict(scene, material={"preset": "marble"}))
    # Paths as pathlib.Path; empty, NUL-holding and missing ones refused as such.
    sim.export(tmp_path / "s.obj")
    sim.save_project(tmp_path / "s.gsproj")
    assert sim.export_tets(tmp_path / "t") == 0
    assert (tmp_path / "s.obj").exists() and (tmp_path / "t.node").exists()
    with pytest.raises(ValueError, match="an empty path"):
        sim.export_tets("")
    with pytest.raises(ValueError, match="names no file"):
        sim.export_tets(str(tmp_path) + "/")
    with pytest.raises(ValueError, match="NUL"):
        sim.save_project(str(tmp_path / "a\0b.gsproj"))
    assert not list(tmp_path.glob("a*")), "nothing written under a cut name"
    with pytest.raises(TypeError):
        sim.export(42)
    with pytest.raises(FileNotFoundError, match="missing.json: no such file"):
        galsculpt.play(tmp_path / "missing.json", tmp_path / "o")


def test_a_number_json_cannot_hold_is_a_value_error_naming_its_key():
    sim = galsculpt.Simulation(BALL)
    with pytest.raises(ValueError, match=r"^event\.radius: nan is not a finite number$"):
        sim.apply({"tool": "brush", "center": [0, 0, 0], "radius": float("nan"),
                   "offset": [0, 0, 0]})
    with pytest.raises(ValueError, match=r"^event\.from\[1\]\[2\]: inf is not a finite number$"):
        sim.apply(dict(KNIFE, **{"from": [[-0.2, 0.2, 0.02], [0.2, 0.2, float("inf")]]}))
    with pytest.raises(ValueError, match=r"solver_options\.residual_tolerance: nan"):
        galsculpt.Simulation(BALL, solver_options={"residual_tolerance": float("nan")})
    assert sim.undo() is False


def test_errors_are_exceptions_with_the_readers_messages(tmp_path):
    with pytest.raises(FileNotFoundError, match="nothing.json: no such file"):
        galsculpt.Simulation(str(tmp_path / "nothing.json"))
    scene = tmp_path / "bad.json"
    scene.write_text(json.dumps({"mesh": {"generate": "sphere", "tets": 500},
                                 "solver": {"newton_iters": 500}}))
    with pytest.raises(ValueError, match=r"bad\.json: \$\.solver\.newton_iters"):
        galsculpt.Simulation(str(scene))
    with pytest.raises(ValueError, match="newton_iters"):
        galsculpt.Simulation(BALL, solver_options={"newton_iters": 0})


def test_solver_options_are_the_tables(ball):
    assert ball.options["newton_iters"] == 40 and ball.options["preset"] == "converged"
    paper = galsculpt.Simulation(BALL, solver_options={"preset": "paper"})
    assert paper.options["newton_iters"] == 1
    assert paper.step()["newton_iterations"] == 1


def test_exports_and_projects(tmp_path):
    sim = galsculpt.Simulation(BALL)
    sim.apply(KNIFE)
    sim.step(2)
    for ext in ("obj", "ply", "stl", "glb"):
        sim.export(str(tmp_path / ("s." + ext)))
        assert (tmp_path / ("s." + ext)).stat().st_size > 0
    sim.export_tets(str(tmp_path / "t.node"))
    for ext in ("node", "ele", "face", "damage", "vtk"):
        assert (tmp_path / ("t." + ext)).exists()
    sim.save_project(str(tmp_path / "p.gsproj"))
    again = galsculpt.Simulation(str(tmp_path / "p.gsproj"))
    assert again.frame == 2 and again.pieces == 2
    assert np.array_equal(again.positions, sim.positions)
    assert np.array_equal(again.damage, sim.damage)
    with pytest.raises(OSError):
        sim.export(str(tmp_path / "no" / "such" / "folder" / "s.obj"))


def test_a_step_runs_without_the_gil():
    sim = galsculpt.Simulation(BALL)
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    thread = threading.Thread(target=tick)
    thread.start()
    time.sleep(0.01)
    start = time.monotonic()
    sim.step(5)
    end = time.monotonic()
    done.set()
    thread.join()
    during = [t for t in ticks if start < t < end]
    assert len(during) >= 3, f"{len(during)} ticks in {end - start:.3f} s of stepping"


def test_a_script_played_from_python_is_the_commands_bit_for_bit(tmp_path):
    played = galsculpt.play(SCRIPT, str(tmp_path / "py"))
    assert "frames" in played["output"] or played["metrics"]
    assert len(played["metrics"]) == json.loads(pathlib.Path(SCRIPT).read_text())["frames"]
    assert {"residual", "converged"} <= set(played["metrics"][0])
    binary = os.environ.get("GALSCULPT_BINARY")
    if binary:
        subprocess.run([binary, "play", SCRIPT, "--out", str(tmp_path / "cli")], check=True,
                       capture_output=True)
        assert (tmp_path / "cli" / "final.obj").read_bytes() == \
            pathlib.Path(played["final_surface"]).read_bytes()
    # The script opened as a Simulation is replayed to its end: the same surface.
    sim = galsculpt.Simulation(SCRIPT)
    sim.export(str(tmp_path / "sim.obj"))
    assert (tmp_path / "sim.obj").read_bytes() == \
        pathlib.Path(played["final_surface"]).read_bytes()
    # play's flags as keyword arguments: one thread gives the same bits.
    threaded = galsculpt.play(SCRIPT, str(tmp_path / "one"), threads=1, export_tets=True)
    assert pathlib.Path(threaded["final_surface"]).read_bytes() == \
        pathlib.Path(played["final_surface"]).read_bytes()
    assert (tmp_path / "one" / "final.node").exists()
    with pytest.raises(FileNotFoundError, match=r"^\S*missing\.json: no such file$"):
        galsculpt.play(str(tmp_path / "missing.json"), str(tmp_path / "x"))
    # Typed keywords: checked as the command checks its flags, the error naming the keyword.
    with pytest.raises(ValueError, match=r"^frames expects an integer in \[1, 100000\], got -1$"):
        galsculpt.bench(frames=-1)
    with pytest.raises(ValueError, match=r"^scene: unknown scene 'sphre' \(did you mean sphere\?\)"):
        galsculpt.bench(scenes=["sphre"])
    with pytest.raises(ValueError, match=r"^settle takes several counts only with cracks$"):
        galsculpt.bench(settle=[0, 40])
    with pytest.raises(ValueError, match=r"^export_format must be obj, ply, stl, gltf or glb"):
        galsculpt.play(SCRIPT, tmp_path / "f", export_format="fbx")
    with pytest.raises(ValueError, match=r"^size expects WIDTHxHEIGHT between 16 and 8192"):
        galsculpt.play(SCRIPT, tmp_path / "f", size=(8, 8))
    with pytest.raises(ValueError, match=r"^backend must be auto, cpu, cuda or device-like, got 'gpu'$"):
        galsculpt.play(SCRIPT, tmp_path / "f", backend="gpu")
    with pytest.raises(ValueError, match=r"^threads expects an integer in \[1, 1024\], got 0$"):
        galsculpt.play(SCRIPT, tmp_path / "f", threads=0)
    with pytest.raises(TypeError):
        galsculpt.play(SCRIPT, tmp_path / "f", nosuch_flag=3)
    assert not (tmp_path / "f").exists(), "nothing written for a call refused"


def test_play_returns_each_frames_row_as_the_metrics_file_holds_it(tmp_path):
    played = galsculpt.play(SCRIPT, tmp_path / "o", metrics=tmp_path / "m.csv", png_every=60,
                            size=(64, 48))
    assert played["metrics_file"] == str(tmp_path / "m.csv")
    lines = (tmp_path / "m.csv").read_text().splitlines()
    header = lines[0].split(",")
    assert len(lines) - 1 == len(played["metrics"])
    for line, row in zip(lines[1:], played["metrics"]):
        for name, cell in zip(header, line.split(",")):
            assert float(cell) == pytest.approx(float(row[name]), rel=1e-5, abs=1e-12), name
    assert {"final.obj", "final.png", "frame_00060.png"} <= set(played["files"])
    assert all((tmp_path / "o" / name).exists() for name in played["files"])
    assert isinstance(played["warnings"], list) and isinstance(played["notes"], list)


def test_bench_returns_what_the_command_writes(tmp_path, monkeypatch):
    # A small hanging sphere in place of the 35k-tet one (as the command's own test does).
    (tmp_path / "scenes").mkdir()
    (tmp_path / "scenes" / "hanging_sphere.json").write_text(json.dumps({
        "mesh": {"file": str(SOURCE / "assets" / "meshes" / "sphere_small.node")},
        "material": {"youngs_modulus": 8000, "poisson_ratio": 0.48, "density": 1000},
        "anchors": [{"box": {"min": [-1, 0.08, -1]}}]}))
    monkeypatch.setenv("GALSCULPT_ASSETS", str(tmp_path))
    result = galsculpt.bench(scenes=["sphere"], frames=2)
    assert result["frames"] == 2 and "machine" in result
    solvers = [row["solver"] for row in result["results"]]
    assert "reference" in solvers and "multigrid" in solvers
    assert all(row["ms_per_frame"] > 0 for row in result["results"])
    assert "sphere" in result["output"]
    # Every other flag of the command as a keyword argument.
    one = galsculpt.bench(scenes=["sphere"], frames=2, threads=1,
                          solver_option={"newton_iters": 3}, debris="keep")
    assert all(row["threads"] == 1 for row in one["results"])
    with pytest.raises(TypeError):
        galsculpt.bench(scenes=["sphere"], frames=2, nosuch_flag=3)
    # json: the same document written there too.
    written = galsculpt.bench(scenes=["sphere"], frames=2, json=tmp_path / "b.json",
                              reference_dir=tmp_path / "refs")
    on_disk = json.loads((tmp_path / "b.json").read_text())
    assert on_disk["frames"] == written["frames"] == 2
    assert [r["solver"] for r in on_disk["results"]] == [r["solver"] for r in written["results"]]
    again = galsculpt.bench(scenes=["sphere"], frames=2, reference_dir=tmp_path / "refs")
    assert again["results"][0].get("reference_cached") is True
