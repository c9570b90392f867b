#!/bin/bash
# Verifies a seeded set of random scenes and prints the pass rate.
#   bench/random-scenes.sh [SEED [COUNT [verify options...]]]
#   bench/random-scenes.sh 1 42                # the set the [random] test runs
#   bench/random-scenes.sh 1 42 --autoscale
# One line per scene (verdict, verify's wall time, the first line of the
# reason), then the counts: pass (exit 0), fail (1), refused (2: the scaling
# says why), abort (3: ngspice aborted or timed out, also on the one retry), how
# many needed the retry, and the slowest run (JOBS=1 for honest wall times).
# KEEP=DIR keeps the scenes and reports there.
# GEARPATCH=path/to/gearpatch (default build/gearpatch); JOBS=n (default 2).
set -eu
seed=${1:-1}
count=${2:-42}
shift $(( $# < 2 ? $# : 2 ))
gearpatch=$(realpath "${GEARPATCH:-build/gearpatch}")
dir=${KEEP:-$(mktemp -d)}
mkdir -p "$dir"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$dir"' EXIT
"$gearpatch" random-scenes --seed "$seed" --count "$count" -o "$dir" 2>/dev/null
verdict() {  # scene.ini verify-options... -> "name verdict reason"
  local scene=$1; shift
  local out=${scene%.ini}.out rc=0 start=$EPOCHREALTIME
  "$gearpatch" verify "$scene" "$@" >"$out" 2>&1 || rc=$?
  local wall=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1fs", b - a }')
  local names=(pass fail refused abort internal)
  local reason=$(grep -E '^  - |gearpatch verify: [^r]' "$out" | grep -m1 -v -E ' done, [0-9]+ failed' | cut -c1-160)
  grep -q '^ngspice retry' "$out" && reason="(ngspice retried) $reason"
  printf '%-36s %-8s %6s %s\n' "$(basename "${scene%.ini}")" "${names[$rc]:-rc$rc}" "$wall" "$reason"
}
export -f verdict
export gearpatch
ls "$dir"/*.ini | parallel -k -j "${JOBS:-2}" verdict {} "$@" | tee "$dir/verdicts.txt"
echo "seed $seed, $count scenes, verify $*:"
for v in pass fail refused abort internal; do
  printf '  %-8s %d\n' "$v" "$(awk -v v=$v '$2 == v' "$dir/verdicts.txt" | wc -l)"
done
printf '  %-8s %d (of the above; ngspice aborted once and the one retry ran)\n' retried \
  "$(grep -c '(ngspice retried)' "$dir/verdicts.txt")"
sort -k3,3 -g "$dir/verdicts.txt" | tail -1 | awk '{ printf "  %-8s %s (%s, %s)\n", "slowest", $3, $1, $2 }'
