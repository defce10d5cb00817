"""Solving from Python: the result's arrays against independent facts, non-convergence as
a warning with the last iterate, the GIL released during a solve, Ctrl-C, and the
convergence study's orders recomputed from its errors."""

import math
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import hemicontact as hc


def test_result_arrays_are_consistent_with_each_other():
    r = hc.solve(hc.paper_example(n=16))
    assert r.converged, r.message
    n_cells = len(r.cells)
    assert r.strain.shape == (n_cells, 3, 3) and r.stress.shape == (n_cells, 3, 3)
    # Symmetric tensors; von Mises from the stress deviator.
    assert np.allclose(r.stress, r.stress.transpose(0, 2, 1), rtol=0, atol=1e-9 * abs(r.stress).max())
    dev = r.stress - np.trace(r.stress, axis1=1, axis2=2)[:, None, None] / 3 * np.eye(3)
    vm = np.sqrt(1.5 * (dev * dev).sum(axis=(1, 2)))
    assert np.allclose(r.von_mises, vm, rtol=1e-12, atol=1e-12 * vm.max())
    assert np.allclose(r.trace_strain, np.trace(r.strain, axis1=1, axis2=2), rtol=1e-12, atol=1e-15)
    c = r.contact
    k = len(c["node"])
    assert k > 0 and all(len(v) == k for v in c.values())
    # The contact points' coordinates are their nodes'; the normals are unit vectors.
    assert np.array_equal(np.stack([c["x"], c["y"]], axis=1), r.points[c["node"]])
    assert np.allclose(np.linalg.norm(c["normal"], axis=1), 1.0)
    # u_nu is the displacement of the node along the normal.
    u_nu = (r.displacement[c["node"]] * c["normal"][:, :2]).sum(axis=1)
    assert np.allclose(c["u_nu"], u_nu, rtol=1e-12, atol=1e-15)
    assert set(c["normal_state"]) <= {"contact", "separated"}
    assert set(c["friction_state"]) <= {"none", "stick", "slip"}
    assert r.history["outer"] and r.history["newton"] and r.timings["total"] > 0
    assert r.certificate["tolerance"] > 0


def test_non_convergence_warns_and_returns_the_last_iterate():
    d = hc.paper_example(n=16).to_dict()
    d["solver"]["outer"]["max_iterations"] = 1
    with pytest.warns(RuntimeWarning, match="converged == False"):
        r = hc.solve(d)
    assert not r.converged
    assert np.all(np.isfinite(r.displacement)) and np.abs(r.displacement).max() > 0


def test_the_gil_is_released_during_a_solve():
    scenario = hc.paper_example(n=128)
    counted = []
    done = threading.Event()

    def count():
        n = 0
        while not done.is_set():
            n += 1
        counted.append(n)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    try:
        hc.solve(scenario)
    finally:
        seconds = time.perf_counter() - start
        done.set()
        counter.join()
    # A Python loop runs millions of iterations a second; with the GIL held by the solve it
    # would run only in the interpreter's 5 ms switch slices before and after.
    assert counted[0] > 100_000 * seconds, (counted, seconds)


CTRL_C = r"""
import os, signal, threading, time
import hemicontact as hc
# Python's own Ctrl-C handler, as in an interactive interpreter: a process started in the
# background by a non-interactive shell inherits SIGINT ignored, and Python then installs none.
signal.signal(signal.SIGINT, signal.default_int_handler)
threading.Timer({delay}, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
t = time.perf_counter()
try:
    {call}
    print("NOT INTERRUPTED")
except KeyboardInterrupt:
    print("interrupted after", round(time.perf_counter() - t, 2), "s")
print("usable", hc.solve(hc.paper_example(n=8)).converged)
"""


def _interrupted_after(call: str, delay: float) -> float:
    """Runs `call` in a fresh interpreter, sends it SIGINT after `delay` s, checks that it
    raised KeyboardInterrupt and that the interpreter then solves again; returns the
    seconds from the start of the call to the interruption."""
    script = CTRL_C.format(call=call, delay=delay)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0].startswith("interrupted after"), out.stdout
    assert lines[1] == "usable True", out.stdout
    return float(lines[0].split()[2])


def test_ctrl_c_interrupts_a_solve_and_leaves_the_interpreter_usable():
    assert _interrupted_after("hc.solve(hc.paper_example(n=512))", 0.3) < 5.0


def test_ctrl_c_interrupts_a_convergence_study():
    # The 512 × 512 reference alone takes several seconds; the study stops within one
    # Newton step of the signal once the reference's system is set up.
    call = "hc.convergence(hc.paper_example(n=8), [8, 16, 32, 64], 512)"
    assert _interrupted_after(call, 0.5) < 5.0


def test_convergence_study_orders_follow_from_its_errors():
    levels = hc.convergence(hc.paper_example(n=4, c_kappa=0.0), [4, 8, 16], 64)
    assert [l["n"] for l in levels] == [4, 8, 16]
    errors = [l["error"] for l in levels]
    assert errors[0] > errors[1] > errors[2] > 0
    for a, b in zip(levels, levels[1:]):
        expected = math.log(a["error"] / b["error"]) / math.log(a["h_edge"] / b["h_edge"])
        assert math.isclose(b["order_edge"], expected, rel_tol=1e-12)
        assert math.isclose(a["h_edge"] / b["h_edge"], 2.0, rel_tol=1e-12)
