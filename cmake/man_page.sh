#!/usr/bin/env bash
# Writes the man page gearpatch.1 from the help texts: help2man reads
# `gearpatch --help` and `--version`; each command's own --help and
# --help-scene go in as sections of their own through an include file.
# usage: man_page.sh GEARPATCH OUTPUT
set -euo pipefail
gearpatch=$1
output=$2
include=$(mktemp)
trap 'rm -f "$include"' EXIT

# Help text as roff: backslashes escaped, a leading dot or quote kept literal.
roff() { sed -e 's/\\/\\e/g' -e "s/^\\([.']\\)/\\\\\\&\\1/"; }

commands=$("$gearpatch" --help | sed -n '/^commands:/,/^$/s/^  \([a-z][a-z-]*\) .*/\1/p')
{
  echo "[COMMANDS]"
  for command in $commands; do
    echo ".SS gearpatch $command"
    echo ".nf"
    "$gearpatch" "$command" --help | roff
    echo ".fi"
  done
  echo "[SCENE FILES]"
  echo ".nf"
  "$gearpatch" --help-scene | roff
  echo ".fi"
  echo "[SEE ALSO]"
  echo "README.md and docs/ in the source tree: the user guide."
} > "$include"
help2man --no-info --no-discard-stderr --section=1 --locale=C.UTF-8 \
  --name="gear drive physics to analog computer programs, checked with ngspice" \
  --include="$include" --output="$output.tmp" "$gearpatch"
# The help texts hold Greek letters and middle dots: tell man's preconv.
{ echo "'\\\" -*- coding: UTF-8 -*-"; cat "$output.tmp"; } > "$output"
rm -f "$output.tmp"
