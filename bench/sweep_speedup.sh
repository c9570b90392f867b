#!/bin/sh
# The sweep runner's parallel speed-up: one 50-point sweep (k over 0 … 1 on
# bild5b, every point with the circuit: --verify runs ngspice) on 1 and on 2
# workers, alternately, REPEAT times each; prints each wall time, the medians,
# the speed-up and the load average before and after (other work on the
# machine slows the 2-worker runs most). Run from the source folder:
#   bench/sweep_speedup.sh [build/gearpatch] [REPEAT]
set -eu
gearpatch=${1:-build/gearpatch}
repeat=${2:-5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in $(seq "$repeat"); do
  for jobs in 1 2; do
    start=$(date +%s.%N)
    "$gearpatch" sweep scenes/bild5b.ini --set gear.restitution=0:1:50 --verify --jobs "$jobs" \
      -o "$out/table.txt" 2>/dev/null
    end=$(date +%s.%N)
    echo "$jobs $(echo "$end - $start" | bc -l)" >> "$out/times"
    echo "run $i, --jobs $jobs: $(echo "$end - $start" | bc -l | cut -c1-6) s"
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
median() { grep "^$1 " "$out/times" | cut -d' ' -f2 | sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
one=$(median 1)
two=$(median 2)
echo "median --jobs 1: $one s, --jobs 2: $two s, speed-up $(echo "$one / $two" | bc -l | cut -c1-5)"
