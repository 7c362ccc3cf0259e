#!/usr/bin/env python3
"""The generated tables of docs/benchmarks.md, from `galsculpt bench --json` results.

  scripts/bench_page.py run NAME [bench options...]   runs `galsculpt bench OPTIONS --json
                                                       docs/bench/NAME.json`, adds where and how it
                                                       ran (commit, machine, command, date), renders
  scripts/bench_page.py render                         renders every docs/bench/*.json again

Each results file fills the part of docs/benchmarks.md between the lines
`<!-- bench_page NAME begin -->` and `<!-- bench_page NAME end -->` (docs/bench/shipped.json,
written by scripts/bench_shipped.py, fills `shipped`), and the index of docs/notes/ fills
`<!-- bench_page notes begin -->` ... `end -->`; the rest of the page is written by hand. Options: --galsculpt PATH (default build/app/galsculpt); with `run`, everything
after NAME goes to `galsculpt bench` (--reference-dir keeps the references between runs).
"""
import datetime
import json
import os
import platform
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PAGE = os.path.join(ROOT, "docs", "benchmarks.md")
BENCH = os.path.join(ROOT, "docs", "bench")


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def git(*args):
    return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True).stdout.strip()


def provenance(command):
    """Where and how a results file was made: commit, date, machine, command."""
    # Changes to the documentation alone do not change what was measured.
    changed = git("status", "--porcelain", "--untracked-files=no", "--", ".", ":!docs", ":!README.md")
    dirty = " (with uncommitted changes)" if changed else ""
    return {
        "commit": git("rev-parse", "--short", "HEAD") + dirty,
        "date": datetime.date.today().isoformat(),
        "machine": f"{cpu_model()}, {os.cpu_count()} cores",
        "command": command,
    }


def run(name, galsculpt, options):
    out = os.path.join(BENCH, name + ".json")
    os.makedirs(BENCH, exist_ok=True)
    command = [galsculpt, "bench", *options, "--json", out + ".tmp"]
    subprocess.run(command, cwd=ROOT, check=True)
    doc = json.load(open(out + ".tmp"))
    doc["provenance"] = provenance("galsculpt bench " + " ".join(options))
    with open(out + ".tmp", "w") as f:
        json.dump(doc, f, indent=2)
        f.write("\n")
    os.replace(out + ".tmp", out)


def number(value, digits):
    return "—" if value is None or value < 0 else f"{value:,.{digits}f}"


def setting(r):
    if r["solver"] == "reference":
        return "reference (Newton, direct solve)"
    cuts = f", {r['cuts']} cuts" if r.get("cuts") is not None else ""
    return f"{r.get('preset', 'multigrid')} {r['grid']}{cuts}"


def device(r):
    """What a frame cost a device backend (bench's launches, barriers and syncs), or a dash."""
    if not r.get("launches"):
        return "—"
    return f"{r['launches']:,.0f} / {r.get('barriers', 0):,.0f} / {r['syncs']:.1f}"


def table(doc):
    """One row per measured setting, speed beside error, as the issues ask for them."""
    p = doc.get("provenance", {})
    lines = [
        f"Machine: {p.get('machine', '?')}; commit {p.get('commit', '?')}, {p.get('date', '?')}; "
        f"`{p.get('command', 'galsculpt bench')}`, {doc['frames']} frames"
        + (f" after {doc['settle_frames']} settling" if doc.get("settle_frames") else "")
        + ". Error in motion: the largest distance to the reference's positions at the motion "
        "frame over the reference's largest displacement; at the end: the same after the last frame; "
        "RMS: the root mean square of the distances over the vertices, over the same displacement.",
        "",
        "| scene | tets | setting | backend | threads | ms/frame | p95 ms | fps | error in motion % "
        "| error at the end % | RMS error at the end % | Newton / CG a frame | largest residual | unconverged frames "
        "| peak MB | device kernels / grid barriers / waits a frame |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in doc["results"]:
        if "error" in r:
            lines.append(f"| {r.get('scene', '?')} | | failed: {r['error']} | | | | | | | | | | | | | |")
            continue
        motion = r.get("rel_position_error_motion")
        end = r.get("rel_position_error")
        rms = r.get("rel_position_error_rms")  # absent from results written before it was
        cached = " (kept reference)" if r.get("reference_cached") else ""
        lines.append(
            f"| {r['scene']} | {r['tets']:,} | {setting(r)}{cached} | {r['backend']} | {r['threads']} "
            f"| {number(r['ms_per_frame'], 1)} | {number(r['ms_p95'], 1)} | {number(r['fps'], 1)} "
            f"| {number(None if motion is None else 100 * motion, 3)} "
            f"| {number(None if end is None else 100 * end, 3)} "
            f"| {number(None if rms is None else 100 * rms, 3)} "
            f"| {r['newton_iters_mean']:.2f} / {r['cg_iters_mean']:.1f} | {r['residual_max']:.2g} "
            f"| {r['unconverged_frames']} of {r['frames']} | {r['peak_rss_mb']:.0f} "
            f"| {device(r)} |")
    return "\n".join(lines)


def shipped_table(doc):
    """scripts/bench_shipped.py's results: every shipped scene and script, a row each."""
    p = doc.get("provenance", {})
    lines = [
        f"Machine: {p.get('machine', '?')}; commit {p.get('commit', '?')}, {p.get('date', '?')}; "
        f"`{p.get('command', 'scripts/bench_shipped.py')}` (`galsculpt run assets/scenes/S.json "
        "--frames N`, `galsculpt play assets/scripts/P.json`, default thread count, one after the "
        "other).",
        "",
        "| scene or script | frames | unconverged frames | warnings | median ms a frame | p95 ms |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    for r in doc["results"]:
        name = r["name"] if r["kind"] == "run" else f"`play` {r['name']}"
        lines.append(f"| {name} | {r['frames']} | {r['unconverged_frames']} | {r['warnings']} "
                     f"| {number(r['ms_per_frame'], 1)} | {number(r['ms_p95'], 1)} |")
    return "\n".join(lines)


def notes_index():
    """The notes, newest first, each by its title (its first line)."""
    folder = os.path.join(ROOT, "docs", "notes")
    lines = []
    for file in sorted((f for f in os.listdir(folder) if f.endswith(".md")), reverse=True):
        title = open(os.path.join(folder, file)).readline().lstrip("# ").strip()
        lines.append(f"- [{title}](notes/{file})")
    return "\n".join(lines)


def render():
    page = open(PAGE).read()
    begin, end = "<!-- bench_page notes begin -->", "<!-- bench_page notes end -->"
    if begin in page:
        page = re.sub(re.escape(begin) + ".*?" + re.escape(end),
                      lambda _: f"{begin}\n{notes_index()}\n{end}", page, flags=re.S)
    for file in sorted(os.listdir(BENCH)):
        if not file.endswith(".json"):
            continue
        name = file[:-5]
        begin, end = f"<!-- bench_page {name} begin -->", f"<!-- bench_page {name} end -->"
        if begin not in page:
            print(f"bench_page: docs/benchmarks.md has no place for {name} ({begin})", file=sys.stderr)
            continue
        doc = json.load(open(os.path.join(BENCH, file)))
        text = shipped_table(doc) if name == "shipped" else table(doc)
        page = re.sub(re.escape(begin) + ".*?" + re.escape(end),
                      lambda _: f"{begin}\n{text}\n{end}", page, flags=re.S)
    with open(PAGE + ".tmp", "w") as f:
        f.write(page)
    os.replace(PAGE + ".tmp", PAGE)


def main(argv):
    galsculpt = os.path.join(ROOT, "build", "app", "galsculpt")
    if "--galsculpt" in argv:
        i = argv.index("--galsculpt")
        galsculpt = argv[i + 1]
        del argv[i:i + 2]
    if len(argv) >= 2 and argv[0] == "run":
        run(argv[1], galsculpt, argv[2:])
        render()
    elif argv == ["render"]:
        render()
    else:
        print(__doc__, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
