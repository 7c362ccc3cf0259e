#!/usr/bin/env python3
"""Threads and the window, measured side by side (docs/benchmarks.md, "Threads and the window").

  scripts/bench_threads_window.py [--build build] [--reps 5] [--frames 20]

1. `galsculpt run` on the hanging sphere at one thread and at the default count, alternating,
   idle and with one other busy process on the machine: median ms a frame and the ratio.
2. The window (under xvfb-run, software GL) on the default scene, the face demo's clay head and
   the hanging sphere, playing, with a grab dragged across the body: the line the window logs
   when it closes (draws a second, ms between draws, the window thread's CPU a draw, the
   simulation's median frame, input to screen), beside `galsculpt run`'s median frame.
3. The window paused and untouched for 10 s: the process's CPU, in % of one core.
Prints Markdown. Nothing else of yours should run meanwhile."""
import argparse, os, re, statistics, subprocess, tempfile, time

ap = argparse.ArgumentParser()
ap.add_argument("--build", default="build")
ap.add_argument("--reps", type=int, default=5)
ap.add_argument("--frames", type=int, default=20)
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
print("| machine state | one thread (ms/frame) | default threads (ms/frame) | default / one |")
print("| --- | --- | --- | --- |")
for busy in (0, 1):
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
print("| scene | window draws/s | ms between draws | window thread ms/draw | "
      "simulation ms/frame in the window | `run` ms/frame | input to screen (ms) |")
print("| --- | --- | --- | --- | --- | --- | --- |")
for name in ("default.json", "clay_head.json", "hanging_sphere.json"):
    scene = os.path.join(scenes, name)
    run_ms(scene, None, 1)
    out = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", binary, "open", scene,
                          "--no-recovery", "--autosave", "0", "--size", "1280x800",
                          "--input-script", script], env=env(), capture_output=True,
                         text=True).stdout
    m = re.search(r"window: (\d+) draws, ([0-9.]+) a second, median ([0-9.]+) ms between draws, "
                  r"([0-9.]+) ms of its thread a draw; simulation: (\d+) frames, median ([0-9.]+)"
                  r" ms a frame; input to screen: median ([0-9.]+) ms", out)
    frames = max(int(m.group(5)), 1) if m else 20
    ms_run = run_ms(scene, None, frames)
    if m:
        print(f"| {name} | {m.group(2)} | {m.group(3)} | {m.group(4)} | {m.group(6)} | "
              f"{ms_run:.1f} | {m.group(7)} |")
    else:
        print(f"| {name} | no summary line: {out[-200:]!r} |")

# Paused and untouched: the process's CPU over 10 s.
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
