#!/usr/bin/env python3
"""Plots results.csv as time per call (log x) against max relative error (log y).

usage: plot.py results.csv benchmark.png [benchmark_all.png]

benchmark.png: small multiples, one panel per algorithm (RNEA, ABA, CRBA, refined forward
dynamics), double only, one colour per library, one marker per model, and a line from our point
to each peer's point of the same model: a line that leaves ours towards the upper right is a
peer both slower and less accurate on that model. Forward-dynamics panels
compare with each peer's forward-dynamics routine (DART's articulated-body solver, KDL's and
MuJoCo's mass-matrix factorisation: the crba_cholesky rows).

benchmark_all.png (default: next to benchmark.png, named <stem>_all.png): every row of the CSV,
every library x algorithm x model x scalar, on one chart."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

if len(sys.argv) not in (3, 4):
    sys.exit(__doc__)
csv_path, png_path = sys.argv[1], sys.argv[2]
all_path = sys.argv[3] if len(sys.argv) == 4 else os.path.splitext(png_path)[0] + "_all.png"

rows = [r for r in csv.DictReader(open(csv_path)) if r["ns_median"] != "nan"]
FLOOR = 1e-19  # an exact result (error 0) is drawn here
CEILING = 1e2  # errors above (float solves of the 1000-body chain) are drawn here, as open markers
EPS = 2.2e-16


def error_of(r):
    err = float(r["max_rel_err"])
    clipped = not math.isfinite(err) or err > CEILING
    return (FLOOR if err == 0 else (CEILING if clipped else err)), clipped


# --- small multiples ---------------------------------------------------------------------------
peers = [  # (library, label, colour), ours first
    ("spatial_dynamics", "spatial_dynamics", "tab:blue"),
    ("kdl", "KDL 1.5.1", "tab:green"),
    ("dart", "DART 6.12", "tab:orange"),
    ("mujoco", "MuJoCo 2.2.2", "tab:red"),
]
# panel title, our algorithm, the peers' algorithms for the same quantity
panels = [
    ("inverse dynamics: RNEA", ["rnea"], ["rnea"]),
    ("forward dynamics: ABA (peers: their forward dynamics)", ["aba"], ["aba", "crba_cholesky"]),
    ("mass matrix: CRBA", ["crba"], ["crba"]),
    ("forward dynamics: aba_refined (peers: their forward dynamics)", ["aba_refined"], ["aba", "crba_cholesky"]),
]
model_markers = ["o", "s", "^", "v", "D", "P", "X", "*", "h", "p", "<", ">", "d", "8"]
double_rows = [r for r in rows if r["scalar"] == "double"]
models = []  # (model, base, dof) in order of size, then name; models only we load (scenes) left out
for r in sorted(double_rows, key=lambda r: (int(r["dof"]), r["model"], r["base"])):
    key = (r["model"], r["base"], int(r["dof"]))
    if key not in models and any(not p["library"].startswith("spatial_dynamics") and (p["model"], p["base"]) == key[:2]
                                 for p in double_rows):
        models.append(key)
marker_of = {m: model_markers[i % len(model_markers)] for i, m in enumerate(models)}


def model_label(m):
    name, base, dof = m
    return f"{name}{' (floating)' if base == 'floating' else ''}, {dof} dof"


fig, axes = plt.subplots(2, 2, figsize=(15, 11.5))
for ax, (title, ours, theirs) in zip(axes.flat, panels):
    points = {}  # library -> {model: (time, error, clipped)}
    for library, label, colour in peers:
        algorithms = ours if library == "spatial_dynamics" else theirs
        for m in models:
            found = [r for r in double_rows if r["library"] == library and (r["model"], r["base"]) == m[:2]
                     and r["algorithm"] in algorithms]
            if found:  # a peer with two routines for the quantity on a model (none in practice): its more accurate one
                r = min(found, key=lambda r: float(r["max_rel_err"]))
                err, clipped = error_of(r)
                points.setdefault(library, {})[m] = (float(r["ns_median"]), err, clipped)
    ours_points = points.get("spatial_dynamics", {})
    for library, label, colour in peers[1:]:  # a spoke from our point to each peer's point of the same model
        for m, (t, err, _) in points.get(library, {}).items():
            if m in ours_points:
                ax.plot([ours_points[m][0], t], [ours_points[m][1], err], color=colour, linewidth=0.8, alpha=0.35,
                        zorder=1)
    for library, label, colour in peers:
        ours_library = library == "spatial_dynamics"
        for m, (t, err, clipped) in points.get(library, {}).items():
            ax.scatter(t, err, marker=marker_of[m], s=75 if ours_library else 55, color="none" if clipped else colour,
                       edgecolors="black" if ours_library else colour, linewidths=0.9, zorder=3 if ours_library else 2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title(title, fontsize=12)
    ax.grid(True, which="major", alpha=0.3)
    ax.axhline(EPS, color="grey", linestyle=":", linewidth=1)
    ax.text(0.99, EPS, "double ε ", color="grey", fontsize=9, ha="right", va="bottom", transform=ax.get_yaxis_transform())
    ax.set_xlabel("time per call, median [ns]")
    ax.set_ylabel("max relative error vs float128")
lib_handles = [Line2D([], [], color=c, marker="o", linewidth=1.5, label=l,
                      markeredgecolor="black" if lib == "spatial_dynamics" else c) for lib, l, c in peers]
model_handles = [Line2D([], [], color="dimgrey", marker=marker_of[m], linestyle="", markersize=8, label=model_label(m))
                 for m in models]
fig.legend(handles=lib_handles, loc="upper left", bbox_to_anchor=(0.0, 1.0), ncol=4, fontsize=11,
           title="library (colour); a line joins our point to each peer's on the same model", title_fontsize=11, frameon=False)
fig.legend(handles=model_handles, loc="center left", bbox_to_anchor=(0.835, 0.5), fontsize=10, title="model (marker)",
           title_fontsize=11, frameon=False)
fig.suptitle("Speed against error, double: lower left is faster and more accurate", x=0.995, y=0.995, ha="right",
             fontsize=13)
fig.tight_layout(rect=(0, 0, 0.83, 0.95))
fig.savefig(png_path, dpi=100)
print("wrote", png_path)

# --- every row on one chart --------------------------------------------------------------------
libraries = {
    ("spatial_dynamics", "double"): ("spatial_dynamics (double)", "tab:blue"),
    ("spatial_dynamics", "float"): ("spatial_dynamics (float)", "tab:cyan"),
    ("kdl", "double"): ("KDL 1.5.1", "tab:green"),
    ("dart", "double"): ("DART 6.12", "tab:orange"),
    ("mujoco", "double"): ("MuJoCo 2.2.2", "tab:red"),
}
markers = {"rnea": "o", "rnea_batch": "P", "aba": "s", "aba_refined": "*", "crba": "^", "crba_cholesky": "D", "gravity": "v", "fk": "x",
           "coriolis_matrix": "h", "observer_update": "p"}

fig, ax = plt.subplots(figsize=(12, 8))
for r in rows:
    label, colour = libraries.get((r["library"], r["scalar"]), (r["library"], "black"))
    err, clipped = error_of(r)
    marker = markers.get(r["algorithm"], ".")
    ax.scatter(float(r["ns_median"]), err, marker=marker, s=36 if r["algorithm"] != "aba_refined" else 90, alpha=0.75,
               linewidths=1.2, color=colour if not clipped or marker == "x" else "none",
               edgecolors=colour if marker != "x" else None)
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("time per call, median [ns] (log scale)")
ax.set_ylabel("max norm-wise relative error vs float128 reference (log scale)")
ax.set_title("Speed against error: every library x algorithm x model x scalar")
ax.grid(True, which="major", alpha=0.3)
ax.set_ylim(top=CEILING * 10)
ax.axhline(EPS, color="grey", linestyle=":", linewidth=1)
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
fig.savefig(all_path, dpi=110)
print("wrote", all_path)
