#!/bin/sh
# The sweep runner's parallel speed-up: one 50-point sweep (k over 0 … 1 on
# bild5b, every point with the circuit at LEVEL: --verify runs ngspice) on 1
# and on 2 workers (bench/speedup.sh). At the ideal level a point takes about
# 35 ms, at the hardware level about 0.3 s. Run from the source folder:
#   bench/sweep_speedup.sh [build/gearpatch] [REPEAT] [ideal|hardware]
set -eu
. "$(dirname "$0")/speedup.sh"
gearpatch=${1:-build/gearpatch}
repeat=${2:-5}
level=${3:-ideal}
table=$(mktemp)
speedup "$repeat" "level $level" "$gearpatch" sweep scenes/bild5b.ini --set gear.restitution=0:1:50 \
  --verify --level "$level" -o "$table"
rm -f "$table"
