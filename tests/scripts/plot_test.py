"""scripts/plot.py: the PNGs it writes from a run's metrics and from bench results, and how it
refuses what it cannot plot."""
import os
import pathlib
import subprocess
import sys

SOURCE = pathlib.Path(__file__).resolve().parents[2]
PLOT = str(SOURCE / "scripts" / "plot.py")
BINARY = os.environ["GALSCULPT_BINARY"]
PNG = b"\x89PNG\r\n\x1a\n"


def plot(*args):
    return subprocess.run([sys.executable, PLOT, *map(str, args)], capture_output=True, text=True)


def metrics(tmp_path):
    subprocess.run([BINARY, "run", str(SOURCE / "assets" / "scenes" / "default.json"), "--frames",
                    "3", "--out", str(tmp_path / "run")], check=True, capture_output=True)
    return tmp_path / "run" / "metrics.csv"


def test_a_runs_metrics_plot_as_panels_against_a_column(tmp_path):
    csv = metrics(tmp_path)
    done = plot("metrics", csv, tmp_path / "m.png")
    assert done.returncode == 0, done.stderr
    assert "ms_total, residual, newton_iterations against frame, 3 rows" in done.stdout
    assert (tmp_path / "m.png").read_bytes().startswith(PNG)
    done = plot("metrics", csv, tmp_path / "load.png", "--x", "time_s", "--y", "load_n,pieces",
                "--log-y")
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "load.png").read_bytes().startswith(PNG)
    assert [p.name for p in tmp_path.iterdir() if p.suffix == ".png"] != [], "no temporary left"
    assert not [p for p in tmp_path.iterdir() if p.name.startswith("tmp")]


def test_what_cannot_be_plotted_is_refused_with_the_reason(tmp_path):
    csv = metrics(tmp_path)
    wrong = plot("metrics", csv, tmp_path / "x.png", "--y", "residul")
    assert wrong.returncode == 2
    assert "has no column 'residul' (did you mean residual" in wrong.stderr
    assert not (tmp_path / "x.png").exists()
    assert plot("metrics", tmp_path / "missing.csv", tmp_path / "x.png").returncode == 3
    cut = tmp_path / "cut.csv"
    lines = csv.read_text().splitlines()
    cut.write_text("\n".join(lines[:2] + [lines[2][: len(lines[2]) // 2]]) + "\n")
    short = plot("metrics", cut, tmp_path / "x.png")
    assert short.returncode == 3 and "cut.csv:3:" in short.stderr, short.stderr
    assert plot("surface", cut, tmp_path / "x.png").returncode == 2
    notbench = tmp_path / "not.json"
    notbench.write_text('{"frames": 3}')
    refused = plot("bench", tmp_path / "b.png", notbench)
    assert refused.returncode == 3 and "not a `galsculpt bench --json` file" in refused.stderr


def test_bench_results_plot_speed_against_error(tmp_path):
    subprocess.run([BINARY, "bench", "--scene", "sphere", "--frames", "2", "--json",
                    str(tmp_path / "b.json")], check=True, capture_output=True)
    done = plot("bench", tmp_path / "b.png", tmp_path / "b.json")
    assert done.returncode == 0, done.stderr
    assert "| sphere |" in done.stdout
    assert (tmp_path / "b.png").read_bytes().startswith(PNG)
