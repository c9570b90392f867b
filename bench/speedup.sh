# Sourced by the *_speedup.sh scripts: runs a gearpatch command on 1 and on 2
# workers alternately, REPEAT times each, and prints each wall and CPU time
# (children included), the medians, the speed-up, and the load average before
# and after (other work on the machine slows the 2-worker runs most).
#   speedup REPEAT LABEL COMMAND...   (COMMAND gets --jobs N appended; exit 1,
#                                      a failed verify, still counts as a run)
speedup() {
  repeat=$1 label=$2
  shift 2
  out=$(mktemp -d)
  echo "$label, load before: $(cut -d' ' -f1-3 /proc/loadavg)"
  for i in $(seq "$repeat"); do
    for jobs in 1 2; do
      /usr/bin/time -f "%e %U %S" -o "$out/time" "$@" --jobs "$jobs" 2>/dev/null || [ $? -eq 1 ]
      read -r wall user sys <<EOF
$(tail -n 1 "$out/time")
EOF
      echo "$jobs $wall" >> "$out/times"
      echo "run $i, --jobs $jobs: wall $wall s, cpu (user+sys, children included) $(echo "$user + $sys" | bc -l) s"
    done
  done
  echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
  one=$(median "$out" 1)
  two=$(median "$out" 2)
  rm -rf "$out"
  echo "median wall: 1 worker $one s, 2 workers $two s, speed-up $(echo "$one / $two" | bc -l | cut -c1-4)x"
}
median() { grep "^$2 " "$1/times" | cut -d' ' -f2 | sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
