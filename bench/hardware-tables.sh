#!/bin/bash
# The hardware level's per-example tables (docs/hardware-circuits.md):
#   bench/hardware-tables.sh perfect          # THE ANALOG THING, perfect components
#   bench/hardware-tables.sh monte-carlo [N [SCENE...]]  # THE ANALOG THING, N drawn machines (default 200)
#   bench/hardware-tables.sh classic          # the classic machine (trimmed offsets)
#   bench/hardware-tables.sh MACHINE          # any other profile with its own offsets (model-1)
# Each example scene is verified at the hardware level at 2 % of full scale.
# perfect and classic: one verify per scene; worst = the largest signal error
# (amplitude after the best shift within the tube), impacts reference/circuit,
# the verdict, and the wall time of the whole verify. monte-carlo: the 10th,
# 50th and 90th percentile of the worst signal over the draws, and the yield.
# GEARPATCH=path/to/gearpatch (default build/gearpatch); run from the repository root.
set -eu
mode=${1:-perfect}
draws=${2:-200}
gearpatch=$(realpath "${GEARPATCH:-build/gearpatch}")
scenes="bild5a bild5b bild5c bild6a bild6b bild6c driven"
[ $# -gt 2 ] && scenes="${*:3}"  # monte-carlo: only these examples
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

verify_row() {  # scene machine -> one table row
  local scene=$1 machine=$2 rc=0 start end
  start=$(date +%s.%N)
  "$gearpatch" verify "scenes/$scene.ini" --level hardware --tolerance 2% --machine "$machine" \
    >"$tmp/$scene.out" 2>&1 || rc=$?
  end=$(date +%s.%N)
  local worst impacts verdict
  worst=$(awk '/^(omega_p|omega_s|dphi|m0) / { if ($4 > w) { w = $4; s = $1 } } END { printf "%.2f (%s)", w, s }' "$tmp/$scene.out")
  impacts=$(sed -n 's/^impacts: reference \([0-9]*\), circuit \([0-9]*\).*/\1\/\2/p' "$tmp/$scene.out")
  case $rc in 0) verdict=PASS ;; 1) verdict=FAIL ;; *) verdict="exit $rc" ;; esac
  printf '| %-7s | %-16s | %-7s | %-7s | %6.1f |\n' "$scene" "$worst" "${impacts:--}" "$verdict" \
    "$(echo "$end - $start" | bc)"
}

case $mode in
perfect | classic | the-analog-thing | model-1 | generic)
  machine=$([ "$mode" = perfect ] && echo bench/the-analog-thing-perfect.ini || echo "$mode")
  echo "| scene   | worst signal %   | impacts | verdict | wall s |"
  echo "|---------|------------------|---------|---------|--------|"
  for scene in $scenes; do verify_row "$scene" "$machine"; done
  ;;
monte-carlo)
  echo "| scene   | draws | worst p10 % | worst p50 % | worst p90 % | yield % |"
  echo "|---------|-------|-------------|-------------|-------------|---------|"
  for scene in $scenes; do
    "$gearpatch" monte-carlo "scenes/$scene.ini" --machine the-analog-thing -n "$draws" >"$tmp/$scene.mc" 2>&1 || true
    awk -v s="$scene" -v n="$draws" '
      /^yield / { y = $2 }
      $1 == "worst" { printf "| %-7s | %5d | %11s | %11s | %11s | %7s |\n", s, n, $2, $3, $4, y }' "$tmp/$scene.mc"
  done
  ;;
*)
  echo "usage: bench/hardware-tables.sh perfect|monte-carlo [N]|classic|the-analog-thing|model-1|generic" >&2
  exit 2
  ;;
esac
