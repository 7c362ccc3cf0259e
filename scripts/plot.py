#!/usr/bin/env python3
"""Plots of what galsculpt writes, as PNG files (gnuplot, which scripts/install-deps.sh installs).

usage:
  scripts/plot.py metrics METRICS.csv OUT.png [--x COLUMN] [--y COLUMN[,COLUMN...]] [--log-y]
      columns of a run's metrics CSV (galsculpt run / play --metrics, docs/cli.md), one panel
      each, against --x (default: frame); default --y: ms_total,residual,newton_iterations.
      A load curve: --x opening_m --y load_n (Charpy).
  scripts/plot.py bench OUT.png BENCH.json [BENCH.json ...]
      speed against error in motion from `galsculpt bench --json` files, every scene in one
      log-log plot, and the same rows as a Markdown table on standard output.

Exit status: 0 when the PNG was written (through a temporary file, renamed); 2 for a usage error
or a column the file does not have (with the nearest names); 3 for a file that cannot be read.
"""
import csv
import difflib
import importlib.util
import json
import os
import subprocess
import sys
import tempfile

# plot-speed-error.py imports its neighbour speed_error_plot.py.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

DEFAULT_Y = ["ms_total", "residual", "newton_iterations"]
# Columns whose values span decades: plotted on a log scale unless they hold a value <= 0.
LOG_COLUMNS = {"residual", "piece_residual", "ms_total", "ms_solve", "ms_elements"}


def fail(code, message):
    sys.stderr.write(f"plot.py: error: {message}\n")
    sys.exit(code)


def read_metrics(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        fail(3, f"{path}: {e.strerror}")
    if not rows or not rows[0]:
        fail(3, f"{path}: empty, not a metrics CSV")
    header = rows[0]
    data = []
    for line, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            fail(3, f"{path}:{line}: {len(row)} fields, the header has {len(header)}")
        try:
            data.append([float(v) for v in row])
        except ValueError:
            fail(3, f"{path}:{line}: a field is not a number")
    if not data:
        fail(3, f"{path}: no rows (no frame finished)")
    return header, data


def column_index(header, name, path):
    if name in header:
        return header.index(name)
    near = difflib.get_close_matches(name, header, n=3)
    hint = f" (did you mean {', '.join(near)}?)" if near else ""
    fail(2, f"{path} has no column '{name}'{hint}")


def gnuplot(script):
    try:
        subprocess.run(["gnuplot"], input=script, text=True, check=True, capture_output=True)
    except FileNotFoundError:
        fail(3, "gnuplot is not installed (scripts/install-deps.sh installs it)")
    except subprocess.CalledProcessError as e:
        fail(3, f"gnuplot failed: {e.stderr.strip()}")


def written(out, draw):
    """Runs draw(temporary path), then renames the temporary file to `out`."""
    directory = os.path.dirname(os.path.abspath(out))
    fd, tmp = tempfile.mkstemp(suffix=".png", dir=directory)
    os.close(fd)
    try:
        draw(tmp)
        if os.path.getsize(tmp) == 0:
            fail(3, f"nothing was drawn into {out}")
        os.replace(tmp, out)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def plot_metrics(args):
    if len(args) < 2:
        fail(2, "metrics needs METRICS.csv OUT.png")
    path, out = args[0], args[1]
    x, ys, log_y = "frame", list(DEFAULT_Y), False
    rest = args[2:]
    while rest:
        flag = rest.pop(0)
        if flag == "--log-y":
            log_y = True
        elif flag in ("--x", "--y") and rest:
            value = rest.pop(0)
            if flag == "--x":
                x = value
            else:
                ys = [c for c in value.split(",") if c]
        else:
            fail(2, f"unknown option '{flag}' (--x COLUMN, --y COLUMN[,...], --log-y)")
    header, data = read_metrics(path)
    xi = column_index(header, x, path)
    yis = [column_index(header, y, path) for y in ys]
    with tempfile.TemporaryDirectory() as tmp:
        table = os.path.join(tmp, "metrics.dat")
        with open(table, "w") as f:
            for row in data:
                f.write(" ".join(repr(v) for v in row) + "\n")

        def draw(target):
            panels = []
            for name, yi in zip(ys, yis):
                values = [row[yi] for row in data]
                log = (log_y or name in LOG_COLUMNS) and min(values) > 0.0
                panels.append(f"""
set ylabel '{name}'
{'set logscale y' if log else 'unset logscale y'}
plot '{table}' using {xi + 1}:{yi + 1} with linespoints pt 7 ps 0.4 notitle
""")
            script = f"""
set terminal pngcairo noenhanced size 1000,{260 * len(ys) + 60} font ',10'
set output '{target}'
set grid
set xlabel '{x}'
set multiplot layout {len(ys)},1 title '{os.path.basename(path)}'
{''.join(panels)}
unset multiplot
"""
            gnuplot(script)

        written(out, draw)
    print(f"wrote {out} ({', '.join(ys)} against {x}, {len(data)} rows)")


def plot_bench(args):
    if len(args) < 2:
        fail(2, "bench needs OUT.png BENCH.json [BENCH.json ...]")
    out, files = args[0], args[1:]
    spec = importlib.util.spec_from_file_location(
        "plot_speed_error", os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                         "plot-speed-error.py"))
    speed_error = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(speed_error)
    for path in files:
        try:
            with open(path) as f:
                doc = json.load(f)
        except OSError as e:
            fail(3, f"{path}: {e.strerror}")
        except json.JSONDecodeError as e:
            fail(3, f"{path}:{e.lineno}: not JSON ({e.msg})")
        if not isinstance(doc, dict) or "results" not in doc:
            fail(3, f"{path}: not a `galsculpt bench --json` file (no results)")
    rows = speed_error.rows_of(files)
    if not rows:
        fail(3, "no measured rows in " + ", ".join(files))
    speed_error.table(rows)
    written(out, lambda target: speed_error.plot(rows, target))
    print(f"wrote {out} ({len(rows)} rows)")


def main():
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) >= 2 else 2)
    kind, args = sys.argv[1], sys.argv[2:]
    if kind == "metrics":
        plot_metrics(args)
    elif kind == "bench":
        plot_bench(args)
    else:
        fail(2, f"unknown plot '{kind}' (metrics or bench; --help)")


if __name__ == "__main__":
    main()
