#!/usr/bin/env bash
# Offline analysis of an LCM log recorded with lcm-logger: one CSV per hapticctrl channel
# (hapticctrl-log2csv) and, per instance found, PNG plots rendered with gnuplot:
#   <instance>.latency_histogram.png  CLOCK wake latency since start (last cycle_stats)
#   <instance>.handle_trajectory.png  handle x, y, z over time, and the x-y path
#   <instance>.forces.png             rendered coupling wrench and operator wrench over time
#
# usage: scripts/plot_log.sh LOG [OUT_DIR] [--build DIR]
# Record first, e.g.: lcm-logger --lcm-url='udpm://239.255.76.67:7667?ttl=0' run.lcmlog
set -euo pipefail
BUILD=build
ARGS=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --build) BUILD=$2; shift 2 ;;
    *) ARGS+=("$1"); shift ;;
  esac
done
[[ ${#ARGS[@]} -ge 1 ]] || { echo "usage: $0 LOG [OUT_DIR] [--build DIR]" >&2; exit 64; }
LOG=${ARGS[0]}
OUT=${ARGS[1]:-${LOG%.*}-csv}
command -v gnuplot >/dev/null || { echo "gnuplot missing (scripts/setup.sh installs gnuplot-nox)" >&2; exit 1; }
# scripts/run.sh builds only what it runs: build the converter when it is not there (J8).
if [[ ! -x $BUILD/bridges/lcm/hapticctrl-log2csv ]]; then
  echo "plot_log: building hapticctrl-log2csv"
  cmake --build "$BUILD" --target hapticctrl-log2csv >/dev/null
fi
"$BUILD/bridges/lcm/hapticctrl-log2csv" --log "$LOG" --out "$OUT"

# Column number of a header name in a CSV file.
col() { head -1 "$1" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }

shopt -s nullglob
for arm in "$OUT"/hapticctrl.*.arm_state.csv; do
  prefix=${arm%.arm_state.csv}
  inst=$(basename "$prefix")
  t=$(col "$arm" utime)
  x=$(col "$arm" handle_pose_x); y=$(col "$arm" handle_pose_y); z=$(col "$arm" handle_pose_z)
  cf=$(col "$arm" rendered_wrench_x); of=$(col "$arm" operator_wrench_x)
  t0=$(sed -n 2p "$arm" | cut -d, -f"$t")
  gnuplot <<GP
set datafile separator ','
set terminal pngcairo size 1200,500 noenhanced
set output '$OUT/$inst.handle_trajectory.png'
set multiplot layout 1,2 title '$inst: handle trajectory (base frame)'
set xlabel 'time [s]'; set ylabel 'position [m]'; set key outside bottom center horizontal
plot '$arm' every ::1 using ((\$$t-$t0)/1e6):$x with lines title 'x', \
     '' every ::1 using ((\$$t-$t0)/1e6):$y with lines title 'y', \
     '' every ::1 using ((\$$t-$t0)/1e6):$z with lines title 'z'
# The path in a square window of at least 2 cm around it: autoscaled, a straight or resting
# path stretched one axis over micrometres of noise and its tick labels ran together (H5).
stats '$arm' every ::1 using $x:$y nooutput
span = STATS_max_x - STATS_min_x > STATS_max_y - STATS_min_y ? STATS_max_x - STATS_min_x : STATS_max_y - STATS_min_y
half = span * 0.55 < 0.01 ? 0.01 : span * 0.55
cx = (STATS_min_x + STATS_max_x) / 2; cy = (STATS_min_y + STATS_max_y) / 2
set xrange [cx - half : cx + half]; set yrange [cy - half : cy + half]; set format '%.3f'
set print '-'
print sprintf('x-y window: x %.4f..%.4f m, y %.4f..%.4f m', cx - half, cx + half, cy - half, cy + half)
set xlabel 'x [m]'; set ylabel 'y [m]'; set size ratio -1
plot '$arm' every ::1 using $x:$y with lines title 'x-y path'
set autoscale; set format '% h'
unset multiplot
set size noratio
set output '$OUT/$inst.forces.png'
set multiplot layout 2,1 title '$inst: forces on the handle (base frame)'
set xlabel 'time [s]'; set ylabel 'rendered coupling [N]'
plot for [i=0:2] '$arm' every ::1 using ((\$$t-$t0)/1e6):(column($cf+i)) with lines \
     title word('fx fy fz', i+1)
set ylabel 'operator [N]'
plot for [i=0:2] '$arm' every ::1 using ((\$$t-$t0)/1e6):(column($of+i)) with lines \
     title word('fx fy fz', i+1)
unset multiplot
GP
  echo "$OUT/$inst.handle_trajectory.png $OUT/$inst.forces.png"
done
for stats in "$OUT"/hapticctrl.*.cycle_stats.csv; do
  inst=$(basename "${stats%.cycle_stats.csv}")
  first=$(col "$stats" wake_histogram_0_2us)
  # The histogram is cumulative since the core started: the last row holds the whole run.
  tail -1 "$stats" | cut -d, -f"$first"- | tr ',' '\n' >"$OUT/$inst.histogram.dat"
  labels=$(head -1 "$stats" | cut -d, -f"$first"- | tr ',' '\n' | sed 's/^wake_histogram_//' | paste -sd' ')
  gnuplot <<GP
set terminal pngcairo size 900,500 noenhanced
set output '$OUT/$inst.latency_histogram.png'
set title '$inst: CLOCK wake-up latency since start (samples per bin)'
set style fill solid 0.8; set boxwidth 0.8; set logscale y; set yrange [0.5:*]
set xtics rotate by -45
labels = '$labels'
plot '$OUT/$inst.histogram.dat' using 0:(\$1 > 0 ? \$1 : 0.5):xtic(word(labels, int(\$0)+1)) \
     with boxes notitle
GP
  echo "$OUT/$inst.latency_histogram.png"
done
