#!/bin/sh
# The sweep runner's parallel speed-up: one 50-point sweep (k over 0 … 1 on
# bild5b, every point with the circuit at LEVEL: --verify runs ngspice) on 1
# and on 2 workers, alternately, REPEAT times each; prints each wall and CPU
# time, the medians, the speed-up, and the load average before and after
# (other work on the machine slows the 2-worker runs most). At the ideal level
# a point takes about 35 ms, at the hardware level about 0.3 s. Run from the
# source folder:
#   bench/sweep_speedup.sh [build/gearpatch] [REPEAT] [ideal|hardware]
set -eu
gearpatch=${1:-build/gearpatch}
repeat=${2:-5}
level=${3:-ideal}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "level $level, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in $(seq "$repeat"); do
  for jobs in 1 2; do
    /usr/bin/time -f "%e %U %S" -o "$out/time" "$gearpatch" sweep scenes/bild5b.ini \
      --set gear.restitution=0:1:50 --verify --level "$level" --jobs "$jobs" -o "$out/table.txt" 2>/dev/null || [ $? -eq 1 ]  # 1: a point failed verify
    read -r wall user sys <<EOF
$(tail -n 1 "$out/time")
EOF
    echo "$jobs $wall" >> "$out/times"
    echo "run $i, --jobs $jobs: wall $wall s, cpu (user+sys, children included) $(echo "$user + $sys" | bc -l) s"
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
median() { grep "^$1 " "$out/times" | cut -d' ' -f2 | sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
one=$(median 1)
two=$(median 2)
echo "median --jobs 1: $one s, --jobs 2: $two s, speed-up $(echo "$one / $two" | bc -l | cut -c1-5)"
