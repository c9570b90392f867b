#!/bin/bash
# The error budget checked for what it claims: per scene the budget's
# prediction of the worst signal (gearpatch budget) against the Monte Carlo's
# p90 of the worst error (gearpatch monte-carlo, seed 1), and their ratio
# (target 0.7…1.5); also the p90's 90 % interval from the draws' order
# statistics, the root-sum-square estimate's ratio, and the per-signal
# ratios' range.
#   bench/budget-vs-monte-carlo.sh MACHINE DRAWS SCENE.ini...
#   bench/budget-vs-monte-carlo.sh the-analog-thing 20 scenes/bild*.ini scenes/driven.ini
#   bench/budget-vs-monte-carlo.sh the-analog-thing 20 random:1:14   # random-scenes --seed 1 --count 14
# One markdown row per scene; a scene whose budget or Monte Carlo could not
# run gets its reason. GEARPATCH=path (default build/gearpatch), JOBS=n
# (default 1), TIMEOUT=s per ngspice run (default 60), KEEP=DIR keeps the JSON
# (a scene whose budget or Monte Carlo JSON is in DIR already is not rerun).
set -eu
machine=$1 draws=$2
shift 2
gearpatch=$(realpath "${GEARPATCH:-build/gearpatch}")
jobs=${JOBS:-1} timeout=${TIMEOUT:-60}
dir=${KEEP:-$(mktemp -d)}
mkdir -p "$dir"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$dir"' EXIT
scenes=()
for s in "$@"; do
  if [[ $s == random:* ]]; then
    IFS=: read -r _ seed count <<<"$s"
    mkdir -p "$dir/random-$seed"
    "$gearpatch" random-scenes --seed "$seed" --count "$count" -o "$dir/random-$seed" 2>/dev/null
    scenes+=("$dir/random-$seed"/*.ini)
  else
    scenes+=("$s")
  fi
done
echo "| scene | budget % (worst signal) | MC p50 % | MC p90 % (90 % interval) | budget / p90 | RSS / p90 | per-signal budget / p90 |"
echo "|---|---|---|---|---|---|---|"
for scene in "${scenes[@]}"; do
  name=$(basename "${scene%.ini}")
  b=$dir/$name.budget.json mc=$dir/$name.mc.json
  why=""
  [ -s "$b" ] || "$gearpatch" budget "$scene" --machine "$machine" -j "$jobs" --timeout "$timeout" --json "$b" \
    >"$dir/$name.budget.txt" 2>&1 || why="budget: exit $? ($(grep -m1 -E 'gearpatch|could not' "$dir/$name.budget.txt" | cut -c1-100))"
  if [ -z "$why" ] && [ ! -s "$mc" ]; then
    "$gearpatch" monte-carlo "$scene" --machine "$machine" -n "$draws" --seed 1 -j "$jobs" --timeout "$timeout" \
      --json "$mc" >"$dir/$name.mc.txt" 2>&1 || why="monte-carlo: exit $? ($(grep -m1 'failed:' "$dir/$name.mc.txt" | cut -c1-100))"
  fi
  if [ -n "$why" ] && [ ! -s "$mc" ]; then
    echo "| $name | $why | | | | | |"
    continue
  fi
  jq -r --arg name "$name" --arg why "$why" --slurpfile b "$b" '
    def r2: . * 100 | round / 100;
    # P(Binomial(n, 0.9) <= k) for k = 0 … n.
    def cdf(n): [range(0; n + 1) | . as $k
      | ([range(1; $k + 1) | (n - . + 1) / .] | map(log) | add // 0) + $k * (0.9 | log) + (n - $k) * (0.1 | log)
      | exp] | reduce .[] as $p ([]; . + [(.[-1] // 0) + $p]);
    # The order statistics that hold the p90 with 90 % confidence (1-based; n + 1: beyond the largest draw).
    def interval(e): (e | length) as $n | cdf($n) as $c
      | (([range(0; $n + 1) | select($c[.] <= 0.05)] | max // -1) + 1) as $r
      | (([range(0; $n + 1) | select($c[.] >= 0.95)] | min) + 1) as $s
      | (e | sort) as $e
      | "\(if $r >= 1 then $e[$r - 1] * 100 | r2 | tostring else "0" end)–\(if $s <= $n then $e[$s - 1] * 100 | r2 | tostring else "above " + ($e[-1] * 100 | r2 | tostring) end)";
    ($b[0]) as $b
    | (.signals | map({(.signal): .}) | add) as $s
    | [$b.predicted | to_entries[] | select($s[.key].p90 > 0) | .value / $s[.key].p90] as $r
    | ([$b.rss | to_entries[] | .value] | max) as $rss
    | "| \($name)\(if $why != "" then " (" + $why + ")" else "" end) | \($b.worst * 100 | r2) (\($b.worst_signal))"
      + " | \($s.worst.p50 * 100 | r2) | \($s.worst.p90 * 100 | r2) (\(interval($s.worst.errors)))"
      + " | \($b.worst / $s.worst.p90 | r2) | \($rss / $s.worst.p90 | r2)"
      + " | \($r | min | r2)–\($r | max | r2) |"' "$mc"
done
