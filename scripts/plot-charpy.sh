#!/usr/bin/env bash
# Load against crack-mouth opening displacement (CMOD) and, where the metrics have them, against
# the striker's displacement with the energy the pendulum lost, from a Charpy run's metrics CSV
# (PNG, gnuplot).
# usage: scripts/plot-charpy.sh METRICS.csv OUT.png
#   galsculpt run assets/scenes/charpy.json --frames 300 --out out --metrics charpy.csv
#   scripts/plot-charpy.sh charpy.csv docs/images/charpy_load_cmod.png
set -euo pipefail
if [[ $# -ne 2 ]]; then
  echo "usage: $0 METRICS.csv OUT.png" >&2
  exit 2
fi
csv=$1
out=$2
[[ -r $csv ]] || { echo "$0: cannot read $csv" >&2; exit 3; }
head -1 "$csv" | grep -q 'opening_m' || { echo "$0: $csv has no opening_m column" >&2; exit 3; }
head -1 "$csv" | grep -q 'load_n' || { echo "$0: $csv has no load_n column" >&2; exit 3; }
tmp="$out.tmp.png"
if head -1 "$csv" | grep -q 'absorbed_energy_j'; then
  gnuplot <<GP
set terminal pngcairo size 1400,560 font ",11"
set output "$tmp"
set datafile separator ","
set grid
set multiplot layout 1,2
set xlabel "crack-mouth opening displacement (mm)"
set ylabel "load on the striker (kN)"
set xrange [0:*]
set yrange [0:*]
plot "$csv" using (column("opening_m")*1000):(column("load_n")/1000) with linespoints pt 7 ps 0.5 title "load against CMOD"
set xlabel "striker displacement (mm)"
set y2label "energy the pendulum lost (J)"
set y2tics
set ytics nomirror
set y2range [0:*]
plot "$csv" using (column("striker_displacement_m")*1000):(column("load_n")/1000) with linespoints pt 7 ps 0.5 title "load", \
     "$csv" using (column("striker_displacement_m")*1000):(column("absorbed_energy_j")) axes x1y2 with lines lw 2 title "absorbed energy"
unset multiplot
GP
else
  gnuplot <<GP
set terminal pngcairo size 900,600 font ",11"
set output "$tmp"
set datafile separator ","
set key autotitle columnhead
set xlabel "crack-mouth opening displacement (mm)"
set ylabel "load on the striker (kN)"
set grid
set xrange [0:*]
set yrange [0:*]
plot "$csv" using (column("opening_m")*1000):(column("load_n")/1000) with linespoints pt 7 ps 0.5 title "Galsculpt, Galerkin multigrid + graph-based FEM"
GP
fi
mv "$tmp" "$out"
echo "wrote $out"
