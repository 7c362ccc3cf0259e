"""docs/quick-start.md as a reader runs it: every `sh` block's commands and the Python block, in
a copy of docs/examples/quick-start, and what they produce checked (the window's `open` is left
out: the window tests drive it)."""
import csv
import os
import pathlib
import re
import shutil
import subprocess
import sys

SOURCE = pathlib.Path(__file__).resolve().parents[2]
PAGE = SOURCE / "docs" / "quick-start.md"
BINARY = pathlib.Path(os.environ["GALSCULPT_BINARY"])


def blocks(language):
    return re.findall(r"```" + language + r"\n(.*?)```", PAGE.read_text(), flags=re.S)


def run(command, cwd, env):
    done = subprocess.run(command, shell=True, cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, f"{command}: exit {done.returncode}\n{done.stdout}\n{done.stderr}"
    return done.stdout + done.stderr


def test_the_quick_start_runs_as_written(tmp_path):
    work = tmp_path / "quick-start"
    shutil.copytree(SOURCE / "docs" / "examples" / "quick-start", work)
    env = dict(os.environ, PATH=f"{BINARY.parent}:{os.environ['PATH']}")
    said = {}
    commands = [line for block in blocks("sh") for line in block.splitlines() if line.strip()]
    assert commands[:2] == ["export PATH=$PWD/build/app:$PATH", "cd docs/examples/quick-start"]
    # The plot script is the repository's, three folders up from the examples.
    os.symlink(SOURCE / "scripts", tmp_path / "scripts", target_is_directory=True)
    for command in commands[2:]:
        if command.startswith("galsculpt open"):
            continue
        if command.startswith("../../../scripts/"):
            command = command.replace("../../../scripts/", "../scripts/")
        said[command] = run(command, work, env)
    assert len(said) >= 8, "every step of the page ran"

    assert "watertight: yes" in said["galsculpt mesh info torus.obj"]
    played = next(text for command, text in said.items() if command.startswith("galsculpt play"))
    assert "0 warning(s)" in played, played
    rows = list(csv.DictReader(open(work / "out" / "metrics.csv")))
    assert len(rows) == 150 and all(float(r["converged"]) == 1 for r in rows)
    assert int(rows[-1]["damaged_edges"]) > 0, "the knife cut the ring"
    for name in ("final.obj", "final.glb", "frame_00050.png", "final.png", "metrics.png"):
        assert (work / "out" / name).stat().st_size > 0, name
    info = said["galsculpt mesh info out/final.glb"]
    assert "watertight: yes" in info and "self_intersections: 0" in info, info
    assert "watertight: yes" in said["galsculpt mesh info out/again.node"]

    # The Python block, run from the folder with the module on the path.
    python = blocks("python")
    assert len(python) == 1
    build_python = BINARY.parent.parent / "python"
    if not any(build_python.glob("galsculpt*.so")):
        return  # built without the module (GALSCULPT_PYTHON=OFF): the module's own tests say so
    out = run(f"{sys.executable} -c {shlex_quote(python[0])}", work,
              dict(env, PYTHONPATH=str(build_python)))
    assert "True []" in out, out
    assert (work / "out" / "more.obj").stat().st_size > 0


def shlex_quote(text):
    import shlex
    return shlex.quote(text)
