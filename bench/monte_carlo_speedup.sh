#!/bin/sh
# The tolerance Monte Carlo's parallel speed-up: 100 draws of bild5b on THE
# ANALOG THING (hardware level, --autoscale) on 1 and on 2 workers,
# alternately, REPEAT times each; prints each wall time, the medians, the
# speed-up, and the load average before and after (other work on the machine
# slows the 2-worker runs most). Run from the source folder:
#   bench/monte_carlo_speedup.sh [build/gearpatch] [REPEAT] [RUNS]
set -eu
gearpatch=${1:-build/gearpatch}
repeat=${2:-3}
runs=${3:-100}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "$runs draws of bild5b on the-analog-thing, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for i in $(seq "$repeat"); do
  for jobs in 1 2; do
    /usr/bin/time -f "%e %U %S" -o "$out/time" "$gearpatch" monte-carlo scenes/bild5b.ini \
      --machine the-analog-thing --autoscale -n "$runs" --seed 1 --jobs "$jobs" -o "$out/table.txt" 2>/dev/null
    read -r wall user sys <<END
$(tail -n 1 "$out/time")
END
    echo "$jobs $wall" >> "$out/times"
    echo "run $i, --jobs $jobs: wall $wall s, cpu (user+sys, children included) $(echo "$user + $sys" | bc -l) s"
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
median() { grep "^$1 " "$out/times" | cut -d' ' -f2 | sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
one=$(median 1)
two=$(median 2)
echo "median wall: 1 worker $one s, 2 workers $two s, speed-up $(echo "$one / $two" | bc -l | cut -c1-4)x"
