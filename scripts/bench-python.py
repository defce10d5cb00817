#!/usr/bin/env python3
"""What the Python path costs over the command line, on the same solve.

Solves a scenario (default: scenarios/paper.toml, the paper's example at n = 128) and
writes its results, alternately with the command-line program (`hemicontact solve FILE
--out DIR`, wall time of the process) and through the Python package in this interpreter
(`hemicontact.solve(hemicontact.load(FILE)).write(DIR)`, wall time of the call), for
`--rounds` rounds, and prints the medians and their ratio. Also prints the median of the
solver's own time (`timings.total`) of the Python solves, and how long the conversion of the
result into numpy arrays takes (the Python-only part), and what a friction coefficient
written in Python costs: the same scenario with the built-in exponential law replaced by the
identical numpy function, per outer iteration and per call; and what a normal compliance
written in Python costs: the built-in linear law replaced by identical numpy functions p and
dp, per Newton step and per call.

Usage: python scripts/bench-python.py [--scenario FILE] [--rounds 7] [--cli PATH]
(needs the package installed, e.g. `bash scripts/test-python.sh` or `pip install
./crates/hemicontact-py`, and a release build of the command line).
"""

import argparse
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

import numpy as np

import hemicontact as hc

REPO = pathlib.Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", default=str(REPO / "scenarios" / "paper.toml"))
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--cli", default=os.environ.get("HEMICONTACT_BIN", str(REPO / "target" / "release" / "hemicontact")))
    args = ap.parse_args()
    cli, py, solver, convert = [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.rounds):
            t = time.perf_counter()
            subprocess.run([args.cli, "solve", args.scenario, "--out", f"{tmp}/cli{k}"],
                           check=True, capture_output=True)
            cli.append(time.perf_counter() - t)
            t = time.perf_counter()
            r = hc.solve(hc.load(args.scenario))
            r.write(f"{tmp}/py{k}")
            py.append(time.perf_counter() - t)
            solver.append(r.timings["total"])
            t = time.perf_counter()
            hc.Result(r._native)
            convert.append(time.perf_counter() - t)
    # A Python law identical to the built-in exponential one (the scenario's mu).
    builtin = hc.load(args.scenario)
    d = builtin.to_dict()
    calls = [0]
    laws = []
    for c in d.get("contact", []):
        mu = c.get("friction", {}).get("mu", {})
        if mu.get("law") == "exponential":
            a, b, beta = mu["a"], mu["b"], mu["beta"]

            def law(r, a=a, b=b, beta=beta):
                calls[0] += 1
                return (a - b) * np.exp(-beta * r) + b

            c["friction"]["mu"] = law
            laws.append(law)
    custom = hc.Scenario.from_dict(d, source=args.scenario) if laws else None
    plain, python, outer, per_call = [], [], [], []
    if custom is not None:
        for _ in range(args.rounds):
            t = time.perf_counter()
            r0 = hc.solve(builtin)
            plain.append(time.perf_counter() - t)
            calls[0] = 0
            t = time.perf_counter()
            r1 = hc.solve(custom)
            python.append(time.perf_counter() - t)
            outer.append(len(r1.history["outer"]))
            per_call.append(calls[0])
    # A Python normal compliance identical to the built-in linear one (the scenario's c_nu).
    d = hc.load(args.scenario).to_dict()
    p_calls = [0]
    compliance = False
    for c in d.get("contact", []):
        if c.get("law") == "normal-compliance":
            c_nu = c.pop("c_nu")
            del c["law"]

            def p(x, c_nu=c_nu):
                p_calls[0] += 1
                return c_nu * x

            def dp(x, c_nu=c_nu):
                p_calls[0] += 1
                return np.full_like(x, c_nu)

            c["normal"] = {"law": "compliance", "p": p, "dp": dp}
            compliance = True
    normal = hc.Scenario.from_dict(d, source=args.scenario) if compliance else None
    n_plain, n_python, n_calls, n_newton = [], [], [], []
    if normal is not None:
        for _ in range(args.rounds):
            t = time.perf_counter()
            hc.solve(builtin)
            n_plain.append(time.perf_counter() - t)
            p_calls[0] = 0
            t = time.perf_counter()
            r2 = hc.solve(normal)
            n_python.append(time.perf_counter() - t)
            n_calls.append(p_calls[0])
            n_newton.append(len(r2.history["newton"]))
    m = statistics.median
    print(f"scenario {args.scenario}, {args.rounds} rounds, medians:")
    print(f"  command line (solve + write, process)   {m(cli):.3f} s")
    print(f"  Python (solve + write, in-process)      {m(py):.3f} s")
    print(f"  ratio Python / command line             {m(py) / m(cli):.3f}")
    print(f"  solver's own time (timings.total)       {m(solver):.3f} s")
    print(f"  result into numpy arrays (Python only)  {m(convert) * 1e3:.1f} ms")
    if python:
        extra = m(python) - m(plain)
        print(f"built-in exponential law                  {m(plain):.3f} s")
        print(f"the same law as a Python function         {m(python):.3f} s "
              f"({m(per_call):.0f} calls, {m(outer):.0f} outer iterations)")
        print(f"  difference per outer iteration          {extra / m(outer) * 1e3:.2f} ms")
        print(f"  difference per call                     {extra / m(per_call) * 1e3:.3f} ms")

    if n_python:
        extra = m(n_python) - m(n_plain)
        print(f"built-in linear normal compliance         {m(n_plain):.3f} s")
        print(f"the same law as Python p and dp           {m(n_python):.3f} s "
              f"({m(n_calls):.0f} calls, {m(n_newton):.0f} Newton steps)")
        print(f"  difference per Newton step              {extra / m(n_newton) * 1e3:.2f} ms")
        print(f"  difference per call                     {extra / m(n_calls) * 1e3:.3f} ms")


if __name__ == "__main__":
    main()
