#!/usr/bin/env python3
"""One line per result from gearpatch's JSON, for the tables the docs quote.

    build/gearpatch verify SCENE --json - 2>/dev/null | docs/tools/summary.py verify
    docs/tools/summary.py figures docs/figures/figures.json
"""
import json
import sys


def verify(result):
    worst = max(s["max_error"] for s in result["signals"].values())
    verdict = "pass" if result["passed"] else "FAIL"
    print(f"beta {result['beta']:<9.6g} worst amplitude error {100 * worst:7.4f} % of full scale  {verdict}")


def figures(path):
    with open(path, encoding="utf-8") as f:
        for figure in json.load(f):
            numbers = figure["figures"]
            k = [abs(r) if abs(r) < 5e-4 else r for r in numbers["restitution"]] or [float("nan")]
            speeds = figure["final_speeds"]
            check = figure["verify"]
            print(f"Bild {figure['bild']}: {numbers['impacts']} impact(s), restitution {min(k):.3f}…{max(k):.3f}, "
                  f"final speeds {speeds[0]:.4f} and {speeds[1]:.4f} rad/s, "
                  f"momentum to friction {numbers['friction_impulse']:.3f} N·m·s, "
                  f"energy dissipated {numbers['dissipated']:.3f} J, "
                  f"circuit within {100 * check['worst_error']:.4f} % ({'pass' if check['passed'] else 'FAIL'})")


if __name__ == "__main__":
    if sys.argv[1:2] == ["verify"]:
        verify(json.load(sys.stdin))
    elif sys.argv[1:2] == ["figures"] and len(sys.argv) == 3:
        figures(sys.argv[2])
    else:
        sys.exit(__doc__)
