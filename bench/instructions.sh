#!/usr/bin/env bash
# Instructions per run of the reference solver, which the machine's load does
# not change: callgrind counts gearpatch::simulate over 11 runs and over 1,
# and the difference / 10 is a warm run (no first-call symbol binding).
# Usage: bench/instructions.sh [BUILD_DIR] [RTOL]   (RTOL: the adaptive solver)
# Prints a line per scene: events, instructions per run and per event.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
rtol=${2:-}
loop="$build/gearpatch_simulate_loop"
command -v valgrind >/dev/null || { echo "needs valgrind (apt-get install valgrind)" >&2; exit 2; }
[ -x "$loop" ] || { echo "no $loop: build with -DGEARPATCH_BENCH=ON" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
count() {  # scene runs -> instructions
  valgrind --tool=callgrind --callgrind-out-file="$work/out" --toggle-collect='gearpatch::simulate*' \
    "$loop" "$1" "$2" $rtol > "$work/events" 2>/dev/null
  callgrind_annotate "$work/out" | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }'
}
printf '%-10s %7s %14s %12s\n' scene events per_run per_event
for scene in long scenes/bild5a.ini scenes/bild5b.ini scenes/bild5c.ini scenes/bild6a.ini \
             scenes/bild6b.ini scenes/bild6c.ini scenes/driven.ini; do
  one=$(count "$scene" 1)
  eleven=$(count "$scene" 11)
  events=$(cat "$work/events")
  per_run=$(( (eleven - one) / 10 ))
  printf '%-10s %7d %14d %12d\n' "$(basename "$scene" .ini)" "$events" "$per_run" $(( per_run / (events > 0 ? events : 1) ))
done
