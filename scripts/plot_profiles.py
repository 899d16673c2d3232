#!/usr/bin/python3
"""Plots of the Christensen-Burley study written by `dermis profile --plot OUTDIR`.

Reads OUTDIR/profile_A*.csv (r_lo, r_hi, r_mid, R_ref, R_ref_stderr, one column per
model) and writes, like Figure 1 of Christensen & Burley 2015 (log vertical axes):
  OUTDIR/profile-study.png      (a) the reference curves r R(r) for every albedo,
                                (b)-(d) the models against the reference at A = 0.2, 0.5, 0.8
                                (the nearest albedos present)
  OUTDIR/profile-study-all.png  one panel per albedo, r R(r) vs r on [0, r_99]
Exit status 3 (and a message) when numpy or matplotlib is missing.
"""
import csv
import glob
import os
import sys

try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as e:  # the caller reports that the plots were skipped
    print(f"plot_profiles.py: {e}; install python3-numpy and python3-matplotlib "
          "(scripts/install-deps.sh)", file=sys.stderr)
    sys.exit(3)

STYLE = {
    "burley_s1": ("Burley (w=A, s=1)", "tab:orange", "--"),
    "cb_volume_mfp": ("C-B fit, s with |A-0.8|^3", "tab:blue", "-"),
    "cb_seed_text": ("C-B fit, s with (0.8-A)^3", "tab:cyan", ":"),
    "dipole": ("dipole (eta as run)", "tab:green", "-."),
    "tabulated": ("tabulated dipole", "tab:olive", (0, (1, 3))),
}


def read_profile(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    return {name: data[:, i] for i, name in enumerate(header)}


def albedo_of(path):
    return float(os.path.basename(path)[len("profile_A"):-len(".csv")])


def energy_radius(p, fraction=0.99):
    area = np.pi * (p["r_hi"] ** 2 - p["r_lo"] ** 2)
    cum = np.cumsum(p["R_ref"] * area)
    i = int(np.searchsorted(cum, fraction * cum[-1]))
    return p["r_hi"][min(i, len(cum) - 1)]


def panel(ax, a, p, legend):
    r = p["r_mid"]
    keep = r > 0
    rr = p["R_ref"] * r
    band = p["R_ref_stderr"] * r
    r_hi = energy_radius(p)
    sel = keep & (p["r_lo"] < r_hi) & (p["R_ref"] > 0)
    ax.fill_between(r[sel], np.maximum(rr[sel] - 2 * band[sel], 1e-30), rr[sel] + 2 * band[sel],
                    color="0.8", label="reference ±2σ")
    ax.plot(r[sel], rr[sel], "k.", ms=3, label="MC reference")
    for key, (label, color, ls) in STYLE.items():
        if key in p:
            ax.plot(r[sel], p[key][sel] * r[sel], color=color, ls=ls, lw=1.2, label=label)
    ax.set_yscale("log")
    ax.set_xlim(0, r_hi)
    ax.set_title(f"A = {a:g}")
    ax.set_xlabel("r (mean free paths)")
    ax.set_ylabel("r R(r)")
    if legend:
        ax.legend(fontsize=7)


def main():
    if len(sys.argv) != 2:
        print("usage: plot_profiles.py OUTDIR", file=sys.stderr)
        return 2
    out = sys.argv[1]
    files = sorted(glob.glob(os.path.join(out, "profile_A*.csv")), key=albedo_of)
    if not files:
        print(f"plot_profiles.py: no profile_A*.csv in {out}", file=sys.stderr)
        return 2
    profiles = [(albedo_of(f), read_profile(f)) for f in files]

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    ax = axes[0][0]
    cmap = plt.get_cmap("viridis")
    for k, (a, p) in enumerate(profiles):
        r = p["r_mid"]
        sel = (r > 0) & (p["R_ref"] > 0) & (r <= 10)
        ax.plot(r[sel], p["R_ref"][sel] * r[sel], color=cmap(k / max(1, len(profiles) - 1)), lw=1, label=f"{a:g}")
    ax.set_yscale("log")
    ax.set_xlim(0, 10)
    ax.set_title("(a) MC reference curves, r R(r)")
    ax.set_xlabel("r (mean free paths)")
    ax.set_ylabel("r R(r)")
    ax.legend(fontsize=6, ncol=2, title="A", title_fontsize=7)
    for k, target in enumerate((0.2, 0.5, 0.8)):
        a, p = min(profiles, key=lambda ap: abs(ap[0] - target))
        panel(axes[(k + 1) // 2][(k + 1) % 2], a, p, legend=(k == 0))
        axes[(k + 1) // 2][(k + 1) % 2].set_title(f"({'bcd'[k]}) A = {a:g}")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "profile-study.png"), dpi=110)
    plt.close(fig)

    n = len(profiles)
    cols = 4
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4 * cols, 3.2 * rows), squeeze=False)
    for k, (a, p) in enumerate(profiles):
        panel(axes[k // cols][k % cols], a, p, legend=(k == 0))
    for k in range(n, rows * cols):
        axes[k // cols][k % cols].axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "profile-study-all.png"), dpi=90)
    plt.close(fig)
    print(f"plot_profiles.py: wrote {out}/profile-study.png and {out}/profile-study-all.png", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
