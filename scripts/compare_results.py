#!/usr/bin/env python3
"""Compares the result folders that two hemicontact binaries wrote for the same runs.

Called by scripts/compare-revisions, which lays out, for every run NAME,
    RUNS/NAME/base/  RUNS/NAME/head/    the output folders (--out) of the two binaries
    RUNS/NAME/base.rc RUNS/NAME/head.rc  their exit codes
A run writes one or more result sets: every folder holding a summary.json (the run's
folder itself for `solve`, locking/ and no-locking/ for `paper`); files outside them
(the paper's comparison figure) form a set of their own, named after the run.

For every result set it compares
  - every file byte for byte; summary.json apart from its "timings" objects;
  - where bytes differ, numerically: each point and cell array of solution.vtu (and its
    points and cells), each column of contact.csv, each numeric field of summary.json
    outside "timings" (fields of a list of objects are grouped over the list, e.g.
    report.newton[].residual). The relative difference of an array is
    max |a - b| / max(max |a|, max |b|);
  - the exit codes of the runs and the `converged` flags;
  - the figures (*.png, *.svg): byte-identical or not (reported, not judged: they are
    drawn from the data compared above);
and reports the solve times (report.timings.total) of both and their ratio.

Residuals (the certificate, the laws' residuals per contact node, Newton residuals, see
RESIDUAL) are round-off at a converged answer: their differences are reported apart and
judged by the converged flags, or against --tolerance with --judge-residuals.

Prints one table, writes it with the details as Markdown to --report, and exits 1 if a
relative difference exceeds --tolerance, an exit code or converged flag differs, a file
exists on one side only, or non-numeric content (text, flags, the number of iterations)
differs; 0 otherwise.
"""

import argparse
import csv
import filecmp
import json
import math
import re
import sys
from pathlib import Path

import meshio
import numpy as np

FIGURE_SUFFIXES = {".png", ".svg"}

# Residuals: how far an answer is from satisfying its equations (the certificate, the
# laws' residuals per contact node, Newton residual histories) and the nodes where they are
# largest. At a converged answer they are round-off, so any change of round-off changes
# them by up to 100 % of themselves: they are reported in a column of their own and judged
# by the converged flags (the certificate), not by --tolerance unless --judge-residuals.
RESIDUAL = re.compile(
    r"residual(?!_tolerance)|round_off|certificate\.(equilibrium|normal_law|friction_law"
    r"|worst_|kkt\.\w*(violation|complementarity|min_multiplier|stick_slip))"
)


class SetResult:
    """The comparison of one result set: differences, flags, iterations and times."""

    def __init__(self, name):
        self.name = name
        self.identical = True  # every file byte-identical (summary.json: apart from timings)
        self.max_abs = 0.0
        self.max_rel = 0.0
        self.max_rel_residual = 0.0
        self.arrays = []  # (relative difference, absolute difference, "file: array")
        self.problems = []  # differences that no tolerance covers (shape, text, files)
        self.added = []  # summary fields new in head and accepted by --new-field
        self.figures = 0  # number of figure files in the set
        self.figures_differ = []
        self.exit_codes = None  # (base, head), on the run's first set
        self.converged = (None, None)
        self.iterations = (None, None)  # ("outer/Newton", ...)
        self.times = (None, None)  # report.timings.total in seconds

    def add_numeric(self, label, abs_diff, rel_diff):
        """Records one numeric comparison (array or scalar group) labelled "file: name"."""
        residual = bool(RESIDUAL.search(label.split(": ", 1)[-1]))
        if abs_diff > 0 or rel_diff > 0:
            self.arrays.append((rel_diff, abs_diff, label + (" (residual)" if residual else "")))
        if residual:
            self.max_rel_residual = max(self.max_rel_residual, rel_diff)
        else:
            self.max_abs = max(self.max_abs, abs_diff)
            self.max_rel = max(self.max_rel, rel_diff)

    def failed(self, tolerance, judge_residuals=False):
        """Whether this set shows a difference beyond what --tolerance allows."""
        codes_differ = self.exit_codes is not None and self.exit_codes[0] != self.exit_codes[1]
        return (
            bool(self.problems)
            or self.max_rel > tolerance
            or (judge_residuals and self.max_rel_residual > tolerance)
            or codes_differ
            or self.converged[0] != self.converged[1]
        )


def array_difference(a, b):
    """Max absolute and relative difference of two equally shaped arrays.

    Equal entries (equal infinities, NaN against NaN) differ by 0; a NaN or infinity
    against anything else differs by infinity. The relative difference is
    max |a - b| / max(max |a|, max |b|) over the finite entries (0/0 = 0).
    """
    a = np.asarray(a, dtype=float).ravel()
    b = np.asarray(b, dtype=float).ravel()
    same = (a == b) | (np.isnan(a) & np.isnan(b))
    with np.errstate(invalid="ignore"):
        diff = np.where(same, 0.0, np.abs(a - b))
    diff = np.where(np.isnan(diff), np.inf, diff)
    abs_diff = float(diff.max()) if diff.size else 0.0
    finite = np.concatenate([np.abs(a[np.isfinite(a)]), np.abs(b[np.isfinite(b)])])
    scale = float(finite.max()) if finite.size else 0.0
    if abs_diff == 0.0:
        return 0.0, 0.0
    return abs_diff, (abs_diff / scale if scale > 0 else math.inf)


def compare_arrays(result, label, a, b):
    """Compares two arrays numerically, or records a shape mismatch."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        result.problems.append(f"{label}: shape {a.shape} vs {b.shape}")
        return
    result.add_numeric(label, *array_difference(a, b))


def compare_vtu(result, rel, base, head):
    """Compares points, cells and every point and cell array of two .vtu files."""
    mb, mh = meshio.read(base), meshio.read(head)
    compare_arrays(result, f"{rel}: points", mb.points, mh.points)
    cells_b = [(c.type, c.data) for c in mb.cells]
    cells_h = [(c.type, c.data) for c in mh.cells]
    if [t for t, _ in cells_b] != [t for t, _ in cells_h] or any(
        db.shape != dh.shape or not np.array_equal(db, dh)
        for (_, db), (_, dh) in zip(cells_b, cells_h)
    ):
        result.problems.append(f"{rel}: cells differ")
    for kind, data_b, data_h in (
        ("point", mb.point_data, mh.point_data),
        ("cell", mb.cell_data, mh.cell_data),
    ):
        if set(data_b) != set(data_h):
            result.problems.append(
                f"{rel}: {kind} arrays {sorted(data_b)} vs {sorted(data_h)}"
            )
        for name in sorted(set(data_b) & set(data_h)):
            a, b = data_b[name], data_h[name]
            if kind == "cell":  # one block per cell type
                a = np.concatenate([np.asarray(x).reshape(len(x), -1) for x in a])
                b = np.concatenate([np.asarray(x).reshape(len(x), -1) for x in b])
            compare_arrays(result, f"{rel}: {kind} {name}", a, b)


def read_csv(path):
    """The header and the columns of a CSV file."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return header, [[row[i] if i < len(row) else "" for row in body] for i in range(len(header))]


def as_floats(column):
    """The column as floats, or None if some entry is not a number."""
    try:
        return np.array([float(x) for x in column])
    except ValueError:
        return None


def compare_csv(result, rel, base, head):
    """Compares every column of two CSV files: numbers numerically, text exactly."""
    hb, cb = read_csv(base)
    hh, ch = read_csv(head)
    if hb != hh:
        result.problems.append(f"{rel}: header {hb} vs {hh}")
        return
    for name, col_b, col_h in zip(hb, cb, ch):
        if len(col_b) != len(col_h):
            result.problems.append(f"{rel}: {len(col_b)} vs {len(col_h)} rows")
            return
        fb, fh = as_floats(col_b), as_floats(col_h)
        if fb is not None and fh is not None:
            compare_arrays(result, f"{rel}: {name}", fb, fh)
        else:
            n = sum(x != y for x, y in zip(col_b, col_h))
            if n:
                result.problems.append(f"{rel}: column {name}: {n} entries differ")


def flatten(value, path, out):
    """Leaves of a JSON value by path, without the "timings" objects."""
    if isinstance(value, dict):
        for key, item in value.items():
            if key != "timings":
                flatten(item, f"{path}.{key}" if path else key, out)
    elif isinstance(value, list):
        for i, item in enumerate(value):
            flatten(item, f"{path}[{i}]", out)
    else:
        out[path] = value


# Summary fields that head adds and that are accepted as a schema addition (--new-field).
NEW_FIELDS = []


def is_number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def compare_summary(result, rel, base, head):
    """Compares the fields of two summary.json files outside "timings".

    Numbers are grouped by their path with list indices dropped (report.newton[].residual),
    so that the relative difference of a history is taken against its largest entry.
    Anything else (text, flags, null, a different number of entries) must be equal.
    """
    leaves_b, leaves_h = {}, {}
    flatten(json.loads(Path(base).read_text()), "", leaves_b)
    flatten(json.loads(Path(head).read_text()), "", leaves_h)
    if leaves_b == leaves_h:
        return True
    groups = {}
    for side, leaves in ((0, leaves_b), (1, leaves_h)):
        for path, value in leaves.items():
            groups.setdefault(re.sub(r"\[\d+\]", "[]", path), ({}, {}))[side][path] = value
    for group, (vb, vh) in sorted(groups.items()):
        if group == "scenario" and {Path(str(v)).name for v in [*vb.values(), *vh.values()]} == {
            Path(str(v)).name for v in vb.values()
        }:
            # The same scenario file name, run from each revision's own folder.
            continue
        if not vb and any(
            group == f or group.startswith((f + ".", f + "[")) for f in NEW_FIELDS
        ):
            if group not in result.added:
                result.added.append(group)
            continue
        if vb.keys() != vh.keys():
            # one message per list: "report.newton[]: 58 vs 56 entries"
            head, _, _ = group.rpartition("[]")
            msg = f"{rel}: {head}[]: {len(vb)} vs {len(vh)} entries" if head else f"{rel}: {group}: missing on one side"
            if msg not in result.problems:
                result.problems.append(msg)
            continue
        paths = sorted(vb)
        if all(is_number(vb[p]) and is_number(vh[p]) for p in paths):
            a = np.array([vb[p] for p in paths], dtype=float)
            b = np.array([vh[p] for p in paths], dtype=float)
            result.add_numeric(f"{rel}: {group}", *array_difference(a, b))
        else:
            for p in paths:
                if vb[p] != vh[p]:
                    result.problems.append(
                        f"{rel}: {p}: {str(vb[p])[:60]!r} vs {str(vh[p])[:60]!r}"
                    )
    return False


def summary_facts(path):
    """converged, "outer/Newton" and the solve time (s) of a summary.json, or Nones."""
    if not path.is_file():
        return None, None, None
    s = json.loads(path.read_text())
    report = s.get("report", {})
    iterations = f"{len(report.get('outer', []))}/{len(report.get('newton', []))}"
    return s.get("converged"), iterations, report.get("timings", {}).get("total")


def result_sets(base, head):
    """Result-set folders (relative) of a run: those holding a summary.json, and the
    run's folder itself if it holds other files; each file goes to its deepest set."""
    files = sorted(
        {p.relative_to(d) for d in (base, head) if d.is_dir() for p in d.rglob("*") if p.is_file()}
    )
    sets = sorted({f.parent for f in files if f.name == "summary.json"})
    owner = {}
    for f in files:
        owner[f] = max((s for s in sets if s in f.parents), key=lambda s: len(s.parts), default=Path("."))
    used = sorted(set(owner.values()))
    return used, owner


def compare_run(name, run_dir):
    """Compares the two output folders of one run; one SetResult per result set."""
    base, head = run_dir / "base", run_dir / "head"
    rc = tuple(int((run_dir / f"{side}.rc").read_text()) for side in ("base", "head"))
    sets, owner = result_sets(base, head)
    if not sets:
        sets = [Path(".")]
    results = {}
    for s in sets:
        r = SetResult(name if s == Path(".") else f"{name}/{s}")
        cb, ib, tb = summary_facts(base / s / "summary.json")
        ch, ih, th = summary_facts(head / s / "summary.json")
        r.converged, r.iterations, r.times = (cb, ch), (ib, ih), (tb, th)
        results[s] = r
    results[sets[0]].exit_codes = rc
    for rel, s in owner.items():
        r = results[s]
        fb, fh = base / rel, head / rel
        if not (fb.is_file() and fh.is_file()):
            r.identical = False
            r.problems.append(f"{rel}: written by {'base' if fb.is_file() else 'head'} only")
            continue
        r.figures += rel.suffix in FIGURE_SUFFIXES
        if filecmp.cmp(fb, fh, shallow=False):
            continue
        if rel.suffix in FIGURE_SUFFIXES:
            r.figures_differ.append(str(rel))
            r.identical = False
        elif rel.name == "summary.json":
            r.identical &= compare_summary(r, str(rel), fb, fh)
        elif rel.suffix == ".vtu":
            r.identical = False
            compare_vtu(r, str(rel), fb, fh)
        elif rel.suffix == ".csv":
            r.identical = False
            compare_csv(r, str(rel), fb, fh)
        else:
            r.identical = False
            r.problems.append(f"{rel}: bytes differ (no numeric comparison for this file)")
    return list(results.values())


def fmt_pair(pair, fmt="{}"):
    """"a" if both sides agree (and are not timings), else "a / b"; None as "—"."""
    a, b = pair

    def show(x):
        if x is None:
            return "—"
        if isinstance(x, bool):
            return "yes" if x else "no"
        return fmt.format(x)

    return show(a) if a == b and fmt == "{}" else f"{show(a)} / {show(b)}"


def row(r, tolerance, judge_residuals):
    """The table's cells for one result set."""
    if r.failed(tolerance, judge_residuals):
        same = "NO"
    elif r.identical:
        same = "yes"
    elif r.arrays:
        same = "within tol."
    elif r.added and not r.figures_differ:
        same = "yes + fields"  # every datum identical; summary.json has accepted new fields
    else:
        same = "data yes"  # only figures differ
    ratio = "—"
    if r.times[0] and r.times[1]:
        ratio = f"{r.times[1] / r.times[0]:.2f}"
    notes = []
    if r.exit_codes is not None:
        notes.append("exit " + fmt_pair(r.exit_codes))
    if r.converged != (None, None):
        notes.append("converged " + fmt_pair(r.converged))
    if r.figures_differ:
        notes.append("figures differ: " + ", ".join(r.figures_differ))
    elif r.figures:
        notes.append("figures identical")
    if r.problems:
        notes.append(f"{len(r.problems)} non-numeric difference(s)")
    if r.added:
        notes.append("new in head: " + ", ".join(r.added))
    return [
        r.name,
        same,
        f"{r.max_rel:.1e}" if r.max_rel else "0",
        f"{r.max_rel_residual:.1e}" if r.max_rel_residual else "0",
        fmt_pair(r.iterations),
        fmt_pair(r.times, "{:.3f}"),
        ratio,
        "; ".join(notes),
    ]


LEGEND = (
    "identical?: yes = every file byte-identical (summary.json apart from timings); "
    "yes + fields = the same, with summary fields new in head (--new-field); "
    "data yes = only figures differ; within tol. = numbers differ by at most the tolerance; "
    "NO = a difference beyond the tolerance, or in exit code, converged flag, files or text. "
    "max rel diff: max |base - head| / max(|base|, |head|) per array, largest over the set's "
    "data; residuals: the same over the residuals (certificate, law residuals, Newton "
    "residuals: round-off at a converged answer, judged through the converged flags)."
)

HEADER = ["case", "identical?", "max rel diff", "residuals", "iterations outer/Newton (base / head)",
          "solve time s (base / head)", "head/base", "notes"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", type=Path, help="folder with one subfolder per run")
    ap.add_argument("--tolerance", type=float, default=1e-12)
    ap.add_argument("--report", type=Path, required=True, help="Markdown report to write")
    ap.add_argument("--meta", action="append", default=[], help="a line for the report's header")
    ap.add_argument("--judge-residuals", action="store_true",
                    help="hold the residuals' differences against --tolerance too")
    ap.add_argument("--skipped", action="append", default=[], help="a run skipped (--quick)")
    ap.add_argument("--new-field", action="append", default=[],
                    help="a summary.json field (dotted path) that only head writes, accepted as a schema addition")
    args = ap.parse_args()
    NEW_FIELDS.extend(args.new_field)

    results = []
    for run_dir in sorted(p for p in args.runs.iterdir() if p.is_dir()):
        results.extend(compare_run(run_dir.name, run_dir))
    judge = args.judge_residuals
    rows = [row(r, args.tolerance, judge) for r in results]
    failed = [r for r in results if r.failed(args.tolerance, judge)]

    widths = [max(len(x) for x in col) for col in zip(HEADER, *rows)]
    for cells in [HEADER, *rows]:
        print("  ".join(c.ljust(w) for c, w in zip(cells, widths)).rstrip())
    tb = sum(r.times[0] or 0 for r in results)
    th = sum(r.times[1] or 0 for r in results)
    total = f"total solve time: base {tb:.3f} s, head {th:.3f} s" + (f", head/base {th / tb:.2f}" if tb else "")
    print(total)
    print(LEGEND)
    for name in args.skipped:
        print(f"skipped (--quick): {name}")
    verdict = (
        f"FAIL: {len(failed)} result set(s) differ beyond tolerance {args.tolerance:g} "
        "or in exit code, converged flag, files or text: " + ", ".join(r.name for r in failed)
        if failed
        else f"OK: every result set is identical or within relative tolerance {args.tolerance:g}"
    )

    md = ["# Comparison of two hemicontact revisions", ""]
    md += [f"- {m}" for m in args.meta]
    md += [f"- tolerance (relative): {args.tolerance:g}", f"- {total}"]
    md += [f"- skipped (--quick): {name}" for name in args.skipped]
    md += ["", "| " + " | ".join(HEADER) + " |", "|" + "---|" * len(HEADER)]
    md += ["| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |" for cells in rows]
    md += ["", LEGEND, "", f"**{verdict}**", ""]
    for r in results:
        if r.arrays or r.problems:
            md += [f"## {r.name}", ""]
            md += [f"- non-numeric: {p}" for p in r.problems]
            for rel, ab, label in sorted(r.arrays, reverse=True):
                md.append(f"- {label}: max rel {rel:.3e}, max abs {ab:.3e}")
            md.append("")
    args.report.parent.mkdir(parents=True, exist_ok=True)
    args.report.write_text("\n".join(md))

    for r in failed:
        if r.exit_codes is not None and r.exit_codes[0] != r.exit_codes[1]:
            print(f"  {r.name}: exit code {fmt_pair(r.exit_codes)}")
        if r.converged[0] != r.converged[1]:
            print(f"  {r.name}: converged {fmt_pair(r.converged)}")
        for p in r.problems[:10]:
            print(f"  {r.name}: {p}")
        judged = [a for a in r.arrays if judge or not a[2].endswith("(residual)")]
        for rel, ab, label in sorted(judged, reverse=True)[:5]:
            print(f"  {r.name}: {label}: max rel {rel:.3e}, max abs {ab:.3e}")
    print(verdict)
    print(f"report: {args.report}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    try:
        main()
    except Exception:  # a broken output or a bug here, not a difference: exit 2, not 1
        import traceback

        traceback.print_exc()
        print("compare_results.py: could not compare (see above)", file=sys.stderr)
        sys.exit(2)
