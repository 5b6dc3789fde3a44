#!/usr/bin/env python3
"""Condenses results.csv into three Markdown tables (inverse dynamics, forward dynamics, mass
matrix): one row per model, one column per library, each cell "max error · median time".
usage: summary.py results.csv summary.md"""
import csv
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
models = []
for r in rows:
    key = (r["model"], r["base"], r["dof"])
    if key not in models:
        models.append(key)
columns = [("spatial_dynamics", "double"), ("spatial_dynamics", "float"), ("kdl", "double"), ("dart", "double"),
           ("mujoco", "double")]
titles = ["spatial_dynamics (double)", "spatial_dynamics (float)", "KDL 1.5.1", "DART 6.12", "MuJoCo 2.2.2"]


def time(ns):
    ns = float(ns)
    return f"{ns / 1e6:.3g} ms" if ns >= 1e6 else (f"{ns / 1e3:.3g} µs" if ns >= 1e3 else f"{ns:.0f} ns")


def cell(model, library, scalar, algorithms, label_algorithm):
    found = [r for r in rows if (r["model"], r["base"], r["dof"]) == model and r["library"] == library
             and r["scalar"] == scalar and r["algorithm"] in algorithms]
    if not found:
        return "—"
    parts = []
    for r in sorted(found, key=lambda r: algorithms.index(r["algorithm"])):
        if r["ns_median"] == "nan":
            parts.append(f"{r['algorithm']}: fails")
            continue
        err = float(r["max_rel_err"])
        text = f"{err:.1e} · {time(r['ns_median'])}" if err == err and err != float("inf") else f"non-finite · {time(r['ns_median'])}"
        parts.append(f"{r['algorithm']} {text}" if label_algorithm else text)
    return "<br>".join(parts)


out = ["Cells: max relative error · median time per call (all rows, with spreads, allocations and state counts: "
       "results.md).\n"]
for title, algorithms, label in [("Inverse dynamics (rnea; rnea_batch: time per state, 64 states per call)",
                                  ["rnea", "rnea_batch"], True),
                                 ("Forward dynamics", ["aba", "aba_refined", "crba_cholesky"], True),
                                 ("Mass matrix (crba)", ["crba"], False)]:
    out.append(f"\n**{title}**\n")
    out.append("| model | base | dof | " + " | ".join(titles) + " |")
    out.append("|---|---|---|" + "---|" * len(titles))
    for m in models:
        out.append(f"| {m[0]} | {m[1]} | {m[2]} | " + " | ".join(cell(m, lib, sc, algorithms, label) for lib, sc in columns) + " |")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("wrote", sys.argv[2])
