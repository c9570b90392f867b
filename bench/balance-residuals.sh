#!/bin/bash
# The energy and momentum balances' residuals of `gearpatch simulate` on the
# example, drive and extreme scenes and on a random set: per scene the larger
# residual as a fraction of its balance's scale (the largest term, or the
# amount stored where that is larger); prints the largest over all.
# Usage: bench/balance-residuals.sh SEED COUNT   (from the repository root)
set -euo pipefail
seed=${1:?seed}; count=${2:?count}
dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
build/gearpatch random-scenes --seed "$seed" --count "$count" -o "$dir/random" >/dev/null 2>&1
python3 - "$dir" scenes/*.ini scenes/drive/*.ini scenes/extremes/*.ini "$dir"/random/*.ini <<'PY'
import json, os, subprocess, sys
folder, scenes = sys.argv[1], sys.argv[2:]
def fraction(b):
    scale = max(b["largest_term"], b["stored"])
    return abs(b["residual"]) / scale if scale else 0.0
worst, runs, refused = (0.0, ""), 0, []
for scene in scenes:
    name = os.path.basename(scene)[:-4]
    run = subprocess.run(["build/gearpatch", "simulate", scene, "-o", folder + "/run.csv", "--summary", "-"],
                         capture_output=True, text=True)
    if run.returncode:
        refused.append(name)
        continue
    balance = json.loads(run.stdout)["balance"]
    runs += 1
    value = max(fraction(balance["energy"]), fraction(balance["momentum"]))
    if value >= worst[0]:
        worst = (value, name)
print(f"{runs} scenes run, largest residual {worst[0]:.1e} of the balance's scale ({worst[1]})")
print(f"refused (too many events, with or without the balance): {', '.join(refused) or 'none'}")
PY
