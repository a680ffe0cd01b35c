"""Writes pp_quasi_cli.json: the command-line tool's quasi-interpolants of x*cos(x) for the
τ rules and for explicit τ values, the reference of test_curves.py::test_quasi_tau_like_cli.

    python make_pp_quasi_cli.py PATH/TO/lekalo
"""

import json
import subprocess
import sys

BREAKPOINTS = "0,0.5,0.9,1.4,2.1,2.7,3"
# a simple, a double and a triple interior knot, so that the rules disagree
CONTINUITY = "2,1,2,0,2"
# one τ per B-spline (11 of them), each inside its support
TAU = "0,0.25,0.7,0.9,1.2,1.8,2.1,2.1,2.5,2.9,3"


def main():
    lekalo = sys.argv[1]
    cases = []
    for choice in (["--rule", "first-interval-midpoint"], ["--rule", "greville"], ["--tau", TAU]):
        cmd = [lekalo, "pp", "quasi", "--function", "x*cos(x)", "--breakpoints", BREAKPOINTS,
               "--order", "3", "--continuity", CONTINUITY, *choice, "--json"]
        out = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
        cases.append({"command": " ".join(cmd[1:]), "choice": choice, "curve": out["curve"]})
    doc = {"breakpoints": [float(x) for x in BREAKPOINTS.split(",")],
           "continuity": [int(x) for x in CONTINUITY.split(",")], "order": 3, "cases": cases}
    with open("pp_quasi_cli.json", "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
