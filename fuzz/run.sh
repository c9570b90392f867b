#!/usr/bin/env bash
# Runs each fuzz target for SECONDS (default 15) from its committed corpus and
# dictionary; exits 1 if any target finds a crash, a hang (an input taking
# over 10 s), a leak or a sanitizer report. The corpus is only read: new
# inputs go to a scratch folder, failing ones to BUILD/fuzz-findings/.
#   usage: fuzz/run.sh BUILD [SECONDS]    (BUILD configured with -DGEARPATCH_FUZZ=ON)
set -uo pipefail
build=$(cd "$1" && pwd)
seconds=${2:-15}
here=$(cd "$(dirname "$0")" && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
findings="$build/fuzz-findings"
mkdir -p "$findings"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-abort_on_error=1:print_stacktrace=1}
status=0
for target in scene stages rawfile deck machine manifest result drive_table; do
  mkdir -p "$scratch/$target"
  log="$scratch/$target.log"
  if "$build/fuzz_$target" -seed="${FUZZ_SEED:-1}" -max_total_time="$seconds" -timeout=10 \
       -rss_limit_mb=2048 -dict="$here/$target.dict" -artifact_prefix="$findings/$target-" \
       "$scratch/$target" "$here/corpus/$target" >"$log" 2>&1; then
    echo "fuzz_$target: no finding in $seconds s: $(tail -n 1 "$log")"
  else
    echo "fuzz_$target: FINDING (input saved under $findings/):"
    tail -n 60 "$log"
    status=1
  fi
done
exit $status
