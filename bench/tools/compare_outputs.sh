#!/usr/bin/env bash
# Runs two gearpatch binaries on every scene of scenes/ (scenes/drive/ and
# scenes/extremes/ included) and compares what they write, byte for byte:
# `settings` (table and --json), `netlist` (ideal and hardware), `patch`
# (sheet and --json; the extremes without the offset check's ngspice runs,
# which take minutes on some) and `simulate` (CSV and --summary JSON), each
# with its stderr and exit status. Prints the differences (a run's
# "seconds" aside) and exits 1 if there are any. A WORK_DIR given again resumes: finished runs are kept.
#
#   bench/tools/compare_outputs.sh BEFORE_BINARY AFTER_BINARY [WORK_DIR]
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 BEFORE_BINARY AFTER_BINARY [WORK_DIR]" >&2; exit 2; }
before=$(realpath "$1") after=$(realpath "$2")
root=$(git rev-parse --show-toplevel)
work=${3:-$(mktemp -d)}
mkdir -p "$work"

# run SIDE NAME ARGS...: the command's files, stdout+stderr and status in SIDE/NAME/.
run() {
  local side=$1 name=$2 bin
  shift 2
  bin=$([ "$side" = before ] && echo "$before" || echo "$after")
  if [ -f "$work/$side/$name/output.txt" ] && tail -n 1 "$work/$side/$name/output.txt" | grep -q '^exit '; then
    return 0
  fi
  rm -rf "${work:?}/$side/$name"
  mkdir -p "$work/$side/$name"
  # its own session: a run that signals its process group hits only itself
  local status=0
  (cd "$work/$side/$name" && setsid "$bin" "$@" > output.txt 2>&1) || status=$?
  echo "exit $status" >> "$work/$side/$name/output.txt"
}

mapfile -t scenes < <(cd "$root" && ls scenes/*.ini scenes/drive/*.ini scenes/extremes/*.ini)
for side in before after; do
  for scene in "${scenes[@]}"; do
    s="$root/$scene" n=${scene//\//_}
    run $side "$n.settings" settings "$s" --json settings.json
    run $side "$n.netlist" netlist "$s"
    run $side "$n.netlist-hardware" netlist "$s" --level hardware
    case $scene in
      scenes/extremes/*) run $side "$n.patch" patch "$s" --json patch.json --no-offset-check ;;
      *) run $side "$n.patch" patch "$s" --json patch.json ;;
    esac
    run $side "$n.simulate" simulate "$s" -o trajectory.csv --summary summary.json
  done
done
files=$(find "$work/before" -type f | wc -l)
# the one field that differs run to run: how long a run took
if diff -r -I '^ *"seconds": [0-9.eE+-]*,\?$' "$work/before" "$work/after"; then
  echo "identical: ${#scenes[@]} scenes, $files files (in $work)"
else
  echo "DIFFERENT (in $work)" >&2
  exit 1
fi
