#!/bin/bash
# How far halving the largest ngspice step moves each scene's circuit result
# (verify --check-step at the ideal level, default options), one line a scene.
#   bench/step-check.sh scenes/*.ini
# GEARPATCH=path/to/gearpatch (default build/gearpatch).
set -eu
gearpatch=${GEARPATCH:-build/gearpatch}
for scene in "$@"; do
  out=$("$gearpatch" verify "$scene" --check-step 2>&1) || true
  change=$(echo "$out" | grep -o 'up to [0-9.e+-]* % of full scale ([0-9.e+-]* of the tolerance)' || echo "no step check")
  printf '%-36s %-6s %s\n' "$(basename "${scene%.ini}")" "$(echo "$out" | grep -m1 -E '^(PASS|FAIL)$' || echo '-')" \
    "$change"
done
