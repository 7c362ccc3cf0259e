#!/usr/bin/env bash
# The GPU checks, run on a lent device machine (docs/benchmarks.md, "CUDA backend"): the binaries
# are built here (Debian 12, nvcc 13, sm_90) and travel with the libraries they need, since the
# device machine has the CUDA toolkit but none of galsculpt's Debian libraries. Make the pack with
# `scripts/device_pack.sh`; then on the device machine, from the repository root:
#   scripts/device_check.sh PACK SECONDS STEP...
# STEP: tests[:FILTER] (gpu_tests), tests0[:FILTER] (without CUDA graphs), testsk[:FILTER]
# (without device programs: a kernel a launch, graphs), sanitize:TOOL:FILTER (under
# compute-sanitizer), bench:SCENE[:FRAMES[:EXTRA]] (bench --backend cuda), nographs:SCENE (the same
# without CUDA graphs), noprograms:SCENE (the same without device programs), profile:SCENE (the
# same, each launch timed: gpu/launch_profile.h), play:SCRIPT (a shipped playback script with
# --backend cuda), run:SCENE[:FRAMES] (run --backend cuda on assets/scenes/SCENE.json, for scenes
# without a reference here). With no STEP, the whole check: gpu_tests, bench on the sphere, the
# human figure, Charpy, Charpy after the break and the cut sphere, the armadillo's run and the face
# demo (about 6 minutes on an H200 with kept references). Each step gets what is left of SECONDS;
# every log and JSON goes to $OUT/results.tar.gz (rewritten after each step) and a summary ends the
# output: bench's rows (ms a frame beside error in motion, and the device's kernels and host waits
# a frame) and, for play and run, frames, ms, unconverged frames, kernels and waits a frame.
set -u
pack=$1
budget=$2
shift 2
if [ $# -eq 0 ]; then
  set -- tests bench:sphere:60 bench:human:60 bench:charpy:60 bench:charpy_after_break:60 \
    bench:sphere_cut:60 run:armadillo:30 play:sculpted_face
fi
start=$(date +%s)
# Logs and JSON go to a work folder packed into $OUT/results.tar.gz after each step, the summary
# beside it: two files come back, whatever the number of steps.
out=${OUT:-/tmp/galsculpt-device-out}
work=$(mktemp -d)
mkdir -p "$out" "$work/r"
root=$PWD
# The test binaries name their data by the absolute path of the checkout they were built in.
if [ ! -e /work/main ]; then mkdir -p /work && ln -s "$root" /work/main; fi
dev=/tmp/galsculpt-dev
mkdir -p "$dev" && tar -C "$dev" -xJf "$pack" || exit 1
cusolver=$(find /usr/local/cuda*/lib64 /usr/local/cuda*/targets/*/lib /opt -name 'libcusolver.so*' \
  2>/dev/null | head -1)
export LD_LIBRARY_PATH="$dev/lib${cusolver:+:$(dirname "$cusolver")}"
export GALSCULPT_CACHE_DIR=$dev/cache GALSCULPT_ASSETS=$root/assets PATH=$dev/bin:$PATH:/usr/local/cuda/bin
[ -d "$dev/refs" ] && export GALSCULPT_REFERENCE_DIR=${GALSCULPT_REFERENCE_DIR:-$dev/refs}
if ! galsculpt --version >/dev/null 2>&1; then export LD_LIBRARY_PATH=$dev/libcxx:$LD_LIBRARY_PATH; fi
{
  nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv
  nproc
  galsculpt --version
  echo "cusolver: ${cusolver:-none}"
  ldd "$dev/bin/galsculpt" | grep -i "not found"
} 2>&1 | tee "$work/r/machine.txt"

left() { echo $((budget - ($(date +%s) - start))); }
summary=$work/r/summary.txt
: >"$summary"
for step in "$@"; do
  t=$(left)
  if [ "$t" -lt 10 ]; then echo "$step: skipped, no time left" | tee -a "$summary"; continue; fi
  IFS=: read -r kind scene frames extra <<<"$step"
  log=$work/r/${step//[:*]/-}.log
  t0=$(date +%s)
  case $kind in
    tests | tests0 | testsk | sanitize)
      # tests[:FILTER], tests0[:FILTER] (without CUDA graphs), sanitize:TOOL:FILTER[:FRAMES]
      # (compute-sanitizer, GALSCULPT_COMPARE_FRAMES frames, default 10).
      run=(gpu_tests "--gtest_filter=${scene:-*}" --gtest_output="xml:$work/r/${step//[:*]/-}.xml")
      envs=(GALSCULPT_DEBUG_COMPARE=1)
      [ "$kind" = tests0 ] && envs+=(GALSCULPT_CUDA_GRAPHS=0)
      [ "$kind" = testsk ] && envs+=(GALSCULPT_CUDA_PROGRAMS=0)
      if [ "$kind" = sanitize ]; then
        run=(compute-sanitizer --tool "$scene" --print-limit 20 gpu_tests "--gtest_filter=$frames")
        envs+=("GALSCULPT_COMPARE_FRAMES=${extra:-10}")
      fi
      timeout "$t" env "${envs[@]}" "${run[@]}" >"$log" 2>&1
      rc=$?
      grep -E "against cpu|^\[       OK|^\[  FAILED|^\[  SKIPPED|Failure|actual|ERROR SUMMARY|Invalid|Uninitialized|Race" \
        "$log" | head -40 >>"$summary"
      ;;
    bench | nographs | noprograms | profile)
      envs=()
      [ "$kind" = nographs ] && envs=(GALSCULPT_CUDA_GRAPHS=0)
      [ "$kind" = noprograms ] && envs=(GALSCULPT_CUDA_PROGRAMS=0)
      [ "$kind" = profile ] && envs=(GALSCULPT_CUDA_PROFILE=1)
      # shellcheck disable=SC2086
      timeout "$t" env ${envs[@]+"${envs[@]}"} galsculpt bench --backend cuda --scene "$scene" \
        --frames "${frames:-60}" --json "$work/r/${step//:/-}.json" \
        ${GALSCULPT_REFERENCE_DIR:+--reference-dir "$GALSCULPT_REFERENCE_DIR"} $extra >"$log" 2>&1
      rc=$?
      cat "$log" >>"$summary"
      ;;
    play | run)
      # play:SCRIPT (assets/scripts/SCRIPT.json), run:SCENE[:FRAMES] (assets/scenes/SCENE.json,
      # default 30 frames), both with --backend cuda: frames, median and p95 ms, unconverged frames
      # from its metrics.
      csv=$work/r/${step//:/-}.csv
      if [ "$kind" = play ]; then
        timeout "$t" galsculpt play "$root/assets/scripts/$scene.json" --backend cuda \
          --out /tmp/galsculpt-play --metrics "$csv" >"$log" 2>&1
      else
        timeout "$t" galsculpt run "$root/assets/scenes/$scene.json" --frames "${frames:-30}" \
          --backend cuda --out /tmp/galsculpt-run --metrics "$csv" >"$log" 2>&1
      fi
      rc=$?
      tail -3 "$log" >>"$summary"
      python3 - "$csv" >>"$summary" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
ms = sorted(float(r["ms_total"]) for r in rows)
if ms:
    print(f"{len(ms)} frames, median {statistics.median(ms):.2f} ms, "
          f"p95 {ms[int(0.95 * (len(ms) - 1))]:.2f} ms, "
          f"unconverged {sum(r['converged'] != '1' for r in rows)}, "
          f"{statistics.mean(float(r.get('launches', 0)) for r in rows):.0f} kernels and "
          f"{statistics.mean(float(r.get('syncs', 0)) for r in rows):.1f} host waits a frame")
PY
      ;;
    *) echo "unknown step $step" >>"$summary"; rc=2 ;;
  esac
  echo "== $step: exit $rc in $(($(date +%s) - t0)) s" | tee -a "$summary"
  tar -C "$work" -czf "$out/results.tar.gz.tmp" r && mv "$out/results.tar.gz.tmp" "$out/results.tar.gz"
  cp "$summary" "$out/summary.txt"
done
cat "$summary"
