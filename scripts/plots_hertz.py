"""Plots of a Hertz run: contact pressure against x on the slave and the
master side with Hertz's curve (the paper's figure 6), sigma_y near the
contact at increments 1, 5, 10, 15, 20 (figures 4-5), and the contact force
against the prescribed displacement for loading and unloading.

The Hertz decks are in mm, N and MPa (input/hertz/hertz.inp says so), the
axes say it; contours use a perceptual colour map (viridis), and stresses
that are round-off of an exact zero (an unloaded increment) are drawn as
zero, not as speckle spread over the whole colour scale."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from gmsh_results import read_msh  # noqa: E402
from hertz import HertzLine  # noqa: E402

__all__ = ["plot_pressure", "plot_sigma_y", "plot_force_displacement", "draw_all"]


def plot_pressure(table, keys, radius, estar, path):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for c, key in zip(colors, keys):
        s, m = table[key]["slave"], table[key]["master"]
        P = float(np.sum(s["force"]))
        if P <= 0:
            continue
        h = HertzLine(P, radius, estar)
        x = np.linspace(-1.2 * h.a, 1.2 * h.a, 400)
        ax.plot(x, h(x), "-", color=c, lw=1.2, label=f"Hertz, increment {key[1]} (P = {P:.4g} N)")
        win = np.abs(s["x"]) < 1.5 * h.a
        ax.plot(s["x"][win], s["pressure"][win], "o", color=c, ms=4, mfc="none", label="slave (cylinder)")
        win = np.abs(m["x"]) < 1.5 * h.a
        ax.plot(m["x"][win], m["pressure"][win], "x", color=c, ms=5, label="master (plate)")
    ax.set_xlabel("x from the cylinder axis (mm)")
    ax.set_ylabel("contact pressure (MPa)")
    ax.set_title("Contact pressure: CFE (slave and master) and Hertz")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def round_off_to_zero(v, scale, rel=1e-9):
    """v with the entries below rel * scale (the largest magnitude over all
    plotted increments) set to 0: an unloaded increment's stresses are
    round-off of zero and would otherwise fill the colour scale."""
    v = np.array(v, dtype=float)
    if scale > 0:
        v[np.abs(v) < rel * scale] = 0.0
    return v


def plot_sigma_y(msh_path, increments, path, window=(-3.0, 3.0, -3.0, 3.0)):
    res = read_msh(msh_path)
    tri = res.triangles()
    steps = res.views["S22"]
    incs = [i for i in increments if i <= len(steps)]
    fig, axes = plt.subplots(1, len(incs), figsize=(3.0 * len(incs) + 1.5, 3.4), squeeze=False,
                             constrained_layout=True)
    x0, x1, y0, y1 = window
    vals = [res.node_view("S22", i - 1)[1][:, 0] for i in incs]
    vals = [round_off_to_zero(v, max(np.nanmax(np.abs(w)) for w in vals)) for v in vals]
    lo = min(np.nanmin(v) for v in vals)
    levels = np.linspace(lo, 0.0 if lo < 0 else 1.0, 21)
    for ax, inc, v in zip(axes[0], incs, vals):
        xy = res.xy.copy()
        if "Displacement" in res.views:
            xy += res.node_view("Displacement", inc - 1)[1][:, :2]
        cs = ax.tricontourf(xy[:, 0], xy[:, 1], tri, np.clip(v, levels[0], levels[-1]), levels=levels,
                            cmap="viridis", extend="both")
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.set_aspect("equal")
        ax.set_title(f"increment {inc}")
        ax.set_xticks([x0, 0, x1])
        ax.set_xlabel("x (mm)")
    axes[0][0].set_ylabel("y (mm)")
    fig.colorbar(cs, ax=axes[0].tolist(), shrink=0.9, label="sigma_y (MPa)")
    fig.suptitle("Vertical stress sigma_y near the contact (deformed)")
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_force_displacement(rows, path):
    u = np.array([-r["u"] for r in rows])
    P = np.array([r["P"] for r in rows])
    peak = int(np.argmax(u))
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.plot(u[: peak + 1], P[: peak + 1], "o-", label="loading")
    ax.plot(u[peak:], P[peak:], "s--", mfc="none", label="unloading")
    ax.set_xlabel("prescribed displacement of the cylinder's top edge (mm)")
    ax.set_ylabel("contact force P (N, thickness 1 mm)")
    ax.set_title("Contact force: loading and unloading")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def draw_all(result_dir, job, table, rows, radius, estar):
    keys = sorted(table)
    loaded = [k for k in keys if np.sum(table[k]["slave"]["force"]) > 0]
    peak = max(loaded, key=lambda k: np.sum(table[k]["slave"]["force"])) if loaded else None
    out = []
    if peak:
        p = os.path.join(result_dir, job + "_pressure.png")
        plot_pressure(table, [peak], radius, estar, p)
        out.append(p)
        mid = [k for k in loaded if k != peak]
        if mid:
            p = os.path.join(result_dir, job + "_pressure_increments.png")
            plot_pressure(table, sorted(set([mid[0], mid[len(mid) // 4], peak])), radius, estar, p)
            out.append(p)
    msh = os.path.join(result_dir, job + ".msh")
    if os.path.exists(msh):
        p = os.path.join(result_dir, job + "_sigma_y.png")
        plot_sigma_y(msh, [1, 5, 10, 15, 20], p)
        out.append(p)
    p = os.path.join(result_dir, job + "_force.png")
    plot_force_displacement(rows, p)
    out.append(p)
    for p in out:
        print("wrote", p)
    return out
