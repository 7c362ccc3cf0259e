#!/usr/bin/env python3
"""Threads and the window, measured side by side (docs/benchmarks.md, "Threads and the window").

  scripts/bench_threads_window.py [--build build] [--reps 5] [--frames 20]

1. `galsculpt run` on the hanging sphere at one thread and at the default count, alternating,
   idle and with one other busy process on the machine: median ms a frame and the ratio.
2. The window (under xvfb-run, software GL) on the default scene, the face demo's clay head and
   the hanging sphere, playing, with a grab dragged across the body: the line the window logs
   when it closes (draws a second, ms between draws, the window thread's CPU a draw, the
   simulation's median frame, input to screen), beside the median frame of the same session
   (its recording, so the same frames, grab included) played headless by `galsculpt play`.
3. The window paused and untouched for 10 s: the process's CPU, in % of one core.
Prints Markdown. Nothing else of yours should run meanwhile."""
import argparse, csv, os, re, statistics, subprocess, tempfile, time

ap = argparse.ArgumentParser()
ap.add_argument("--build", default="build")
ap.add_argument("--reps", type=int, default=5)
ap.add_argument("--frames", type=int, default=20)
ap.add_argument("--window-only", action="store_true", help="only part 2")
ap.add_argument("--scenes", default="default.json,clay_head.json,hanging_sphere.json")
a = ap.parse_args()
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
binary = os.path.join(root, a.build, "app", "galsculpt")
scenes = os.path.join(root, "assets", "scenes")
tmp = tempfile.mkdtemp(prefix="galsculpt-bench-tw-")

def env(threads=None):
    e = dict(os.environ)
    e.pop("OMP_NUM_THREADS", None)
    e.pop("GALSCULPT_THREADS", None)
    if threads: e["GALSCULPT_THREADS"] = str(threads)
    e["GALSCULPT_RECOVERY_DIR"] = os.path.join(tmp, "recovery")
    return e

def run_ms(scene, threads, frames):
    out = subprocess.run([binary, "run", scene, "--frames", str(frames), "--out",
                          os.path.join(tmp, "run")], env=env(threads), capture_output=True,
                         text=True).stdout
    return float(re.search(r"([0-9.]+) ms/frame,", out).group(1))

def hogs(n):
    return [subprocess.Popen(["sh", "-c", "while :; do :; done"]) for _ in range(n)]

sphere = os.path.join(scenes, "hanging_sphere.json")
run_ms(sphere, 1, 1)  # the mesh into the cache
if not a.window_only:
    print("| machine state | one thread (ms/frame) | default threads (ms/frame) | default / one |")
    print("| --- | --- | --- | --- |")
for busy in ((0, 1) if not a.window_only else ()):
    procs = hogs(busy)
    one, dflt = [], []
    try:
        for _ in range(a.reps):
            one.append(run_ms(sphere, 1, a.frames))
            dflt.append(run_ms(sphere, None, a.frames))
    finally:
        for p in procs: p.kill()
    m1, md = statistics.median(one), statistics.median(dflt)
    state = "idle" if busy == 0 else "one core taken by a busy process"
    print(f"| {state} | {m1:.1f} | {md:.1f} | {md / m1:.2f} |")

grab = {"realtime": True, "steps": [
    {"wait_frames": 3}, {"key": "G"}, {"move": [0.5, 0.4]}, {"press": "left"}] +
    [{"move": [0.5 + 0.004 * k, 0.4 - 0.004 * k]} for k in range(1, 60)] +
    [{"release": "left"}, {"wait_frames": 3}]}
script = os.path.join(tmp, "grab.json")
with open(script, "w") as f:
    import json; json.dump(grab, f)
print()
def played_ms(recording):
    # The same frames headless: the session's recording through `galsculpt play`.
    out = os.path.join(tmp, "play")
    metrics = os.path.join(tmp, "play.csv")
    subprocess.run([binary, "play", recording, "--out", out, "--metrics", metrics], env=env(),
                   capture_output=True, check=True)
    with open(metrics) as f:
        rows = list(csv.DictReader(f))
    return statistics.median(float(r["ms_total"]) for r in rows)

print(f"Each figure the median of {a.reps} sessions; the ratio is each session's own.")
print()
print("| scene | draws/s during the grab | draws/s over the session | ms between draws | "
      "window thread ms/draw | simulation ms/frame in the window | "
      "the same frames played headless (ms/frame) | window / headless | input to screen (ms) |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
summary = re.compile(r"window: (\d+) draws, ([0-9.]+) a second, median ([0-9.]+) ms between "
                     r"draws, ([0-9.]+) ms of its thread a draw; simulation: (\d+) frames, median "
                     r"([0-9.]+) ms a frame; input to screen: median ([0-9.]+) ms")
strokes = re.compile(r"during strokes: ([0-9.]+) draws a second")
for name in a.scenes.split(","):
    scene = os.path.join(scenes, name)
    run_ms(scene, None, 1)
    rows = []
    for _ in range(a.reps):
        recording = os.path.join(tmp, "session.json")
        out = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", binary, "open",
                              scene, "--no-recovery", "--autosave", "0", "--size", "1280x800",
                              "--input-script", script, "--save-recording", recording],
                             env=env(), capture_output=True, text=True).stdout
        m = summary.search(out)
        if not m:
            print(f"| {name} | no summary line: {out[-200:]!r} |")
            break
        window, played = float(m.group(6)), played_ms(recording)
        grab = strokes.search(out)
        rows.append((float(m.group(2)), float(m.group(3)), float(m.group(4)), window, played,
                     window / played, float(m.group(7)), float(grab.group(1)) if grab else -1))
    if rows:
        med = [statistics.median(r[k] for r in rows) for k in range(8)]
        print(f"| {name} | {med[7]:.1f} | {med[0]:.1f} | {med[1]:.1f} | {med[2]:.2f} | "
              f"{med[3]:.1f} | {med[4]:.1f} | {med[5]:.2f} | {med[6]:.0f} |")

# Paused and untouched: the process's CPU over 10 s.
if a.window_only: raise SystemExit
proc = subprocess.Popen(["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", binary, "open",
                         os.path.join(scenes, "default.json"), "--paused", "--no-recovery",
                         "--autosave", "0"], env=env(), stdout=subprocess.DEVNULL,
                        stderr=subprocess.DEVNULL)
time.sleep(8)
pid = subprocess.run(["pgrep", "-n", "-f", binary + " open"], capture_output=True,
                     text=True).stdout.strip()
def cpu_s(pid):
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
c0, t0 = cpu_s(pid), time.time()
time.sleep(10)
c1, t1 = cpu_s(pid), time.time()
proc.terminate()
subprocess.run(["pkill", "-f", binary + " open"])
proc.wait()
print()
print(f"Paused and untouched (default scene, 10 s): {100 * (c1 - c0) / (t1 - t0):.1f} % of one core.")
