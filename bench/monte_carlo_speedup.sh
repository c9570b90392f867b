#!/bin/sh
# The tolerance Monte Carlo's parallel speed-up: RUNS draws of bild5b on THE
# ANALOG THING (hardware level, --autoscale) on 1 and on 2 workers
# (bench/speedup.sh). Run from the source folder:
#   bench/monte_carlo_speedup.sh [build/gearpatch] [REPEAT] [RUNS]
set -eu
. "$(dirname "$0")/speedup.sh"
gearpatch=${1:-build/gearpatch}
repeat=${2:-3}
runs=${3:-100}
table=$(mktemp)
speedup "$repeat" "$runs draws of bild5b on the-analog-thing" "$gearpatch" monte-carlo scenes/bild5b.ini \
  --machine the-analog-thing --autoscale -n "$runs" --seed 1 -o "$table"
rm -f "$table"
