#!/usr/bin/env python3
"""Plots results.csv: time per call (log x) against max relative error (log y), one point per
library x algorithm x model x scalar. Colour: library and scalar; marker: algorithm.
usage: plot.py results.csv benchmark.png"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["ns_median"] != "nan"]
libraries = {
    ("spatial_dynamics", "double"): ("spatial_dynamics (double)", "tab:blue"),
    ("spatial_dynamics", "float"): ("spatial_dynamics (float)", "tab:cyan"),
    ("kdl", "double"): ("KDL 1.5.1", "tab:green"),
    ("dart", "double"): ("DART 6.12", "tab:orange"),
    ("mujoco", "double"): ("MuJoCo 2.2.2", "tab:red"),
}
markers = {"rnea": "o", "rnea_batch": "P", "aba": "s", "aba_refined": "*", "crba": "^", "crba_cholesky": "D", "gravity": "v", "fk": "x"}
FLOOR = 1e-19  # an exact result (error 0) is drawn here
CEILING = 1e2  # errors above (float solves of the 1000-body chain) are drawn here, as open markers

fig, ax = plt.subplots(figsize=(12, 8))
for r in rows:
    label, colour = libraries.get((r["library"], r["scalar"]), (r["library"], "black"))
    err = float(r["max_rel_err"])
    clipped = not math.isfinite(err) or err > CEILING
    err = FLOOR if err == 0 else (CEILING if clipped else err)
    marker = markers.get(r["algorithm"], ".")
    ax.scatter(float(r["ns_median"]), err, marker=marker, s=36 if r["algorithm"] != "aba_refined" else 90, alpha=0.75,
               linewidths=1.2, color=colour if not clipped or marker == "x" else "none",
               edgecolors=colour if marker != "x" else None)
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("time per call, median [ns] (log scale)")
ax.set_ylabel("max norm-wise relative error vs float128 reference (log scale)")
ax.set_title("Speed against error: every library x algorithm x model (shared robots, random chains, tree, mass-span chain)")
ax.grid(True, which="major", alpha=0.3)
ax.set_ylim(top=CEILING * 10)
ax.axhline(2.2e-16, color="grey", linestyle=":", linewidth=1)
ax.text(ax.get_xlim()[1] / 1.2, 3e-16, "double ε", color="grey", fontsize=8, ha="right")
ax.axhline(CEILING, color="grey", linestyle="--", linewidth=0.8)
ax.text(ax.get_xlim()[1] / 1.2, CEILING * 1.5, "errors > 1e2 or non-finite, drawn here (open markers)", color="grey",
        fontsize=8, ha="right")
present_libs = {(r["library"], r["scalar"]) for r in rows}
present_algs = {r["algorithm"] for r in rows}
handles = [Line2D([], [], color=c, marker="o", linestyle="", label=l) for k, (l, c) in libraries.items() if k in present_libs]
handles += [Line2D([], [], color="black", marker=m, linestyle="", label=a, markerfacecolor="none" if m != "x" else None)
            for a, m in markers.items() if a in present_algs]
ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), title="library (colour) / algorithm (marker)")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
print("wrote", sys.argv[2])
