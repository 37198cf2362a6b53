#!/usr/bin/env python3
"""The ironing case's die forces against the reference curves (cases/ironing.opts,
scripts/make_ironing_case.py, doc/notes/ironing.md).

usage: ironing_compare.py OUT [--extra DIR:LABEL[:T]]... [--log FILE] [--figure PNG] [--no-figure]

  OUT        the run's output folder (history.csv, contact.csv; fields.h5 for the thickness)

Prints the table of the die's vertical and horizontal forces per unit thickness (the reactions of
die_top: -press_fz / T and drag_fx / T, in units of 1e8 like the reference) at a few times of the
press and slide positions, beside the reference (doc/reference/ironing_force_reference.csv,
interpolated between its markers), the ratio F_x / F_z and the friction ratio of the pair
(force_tangential / force in contact.csv: the friction resultant over the sum of the normal
forces) during the steady slide, the balance of the contact resultant against the reactions, the
Newton iterations and, with --log, the cuts and the wall time. Writes doc/figures/ironing.png:
both forces against time with the reference, and the ratios against the slide.

--extra adds another run's curves to the figure and the table (LABEL in the legend; T its
thickness when fields.h5 is not there to give it).
"""
import argparse
import csv
import os
import re
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
REF = os.path.join(ROOT, "doc", "reference", "ironing_force_reference.csv")
FIG = os.path.join(ROOT, "doc", "figures", "ironing.png")
MU = 0.3
SLIDE_RATE = 10.0        # slide = 10 (t - 1)


def reference(path=REF):
    s = {}
    with open(path) as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            s.setdefault(r["series"], []).append((float(r["time"]), float(r["force"])))
    return {k: np.array(sorted(v)) for k, v in s.items()}


def thickness(out, given=None):
    if given:
        return float(given)
    try:
        import h5py
        with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
            y = f["/mesh/coordinates"][:, 1]
            return float(y.max() - y.min())
    except (OSError, KeyError, ImportError):
        sys.exit("%s: no fields.h5 to read the thickness from; give it (DIR:LABEL:T)" % out)


def run(out, T=None):
    h = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    c = {r["step"]: r for r in csv.DictReader(open(os.path.join(out, "contact.csv")))}
    T = thickness(out, T)
    t = np.array([float(r["time"]) for r in h])
    fz = np.array([-float(r["press_fz"]) for r in h]) / T
    fx = np.array([float(r["drag_fx"]) for r in h]) / T
    rows = [c.get(r["step"]) for r in h]
    # the contact resultant (on the slave set; the die's force is it or its opposite) and the friction
    cz = np.array([abs(float(r["fz"])) if r else np.nan for r in rows]) / T
    cx = np.array([abs(float(r["fx"])) if r else np.nan for r in rows]) / T
    fn = np.array([float(r["force"]) if r else np.nan for r in rows])
    ft = np.array([float(r["force_tangential"]) if r else np.nan for r in rows])
    with np.errstate(invalid="ignore", divide="ignore"):
        fric = np.where(fn > 0, ft / fn, np.nan)
    its = np.array([int(r["newton_its"]) for r in h])
    slip = np.array([int(r["slip"]) if r else 0 for r in rows])
    act = np.array([int(r["active"]) if r else 0 for r in rows])
    return dict(t=t, fz=fz, fx=fx, cz=cz, cx=cx, fric=fric, its=its, slip=slip, active=act, T=T, out=out)


def at(r, key, t):
    """the run's value at time t (linear between steps), nan past its last step"""
    if t > r["t"][-1] + 1e-9:
        return float("nan")
    return float(np.interp(t, r["t"], r[key]))


def logstats(path):
    if not path or not os.path.exists(path):
        return None
    txt = open(path).read()
    m = re.search(r"done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts, ([0-9.]+) s", txt)
    last = re.findall(r"step +(\d+) +time ([0-9.]+) +its +\d+ .*elapsed ([0-9.]+) s", txt)
    return dict(done=m.groups() if m else None, cuts=txt.count("retrying with increment"),
                last=last[-1] if last else None, error=re.search(r"atrito: error: (.*)", txt))


def table(runs, ref):
    times = [0.4, 0.6, 0.8, 1.0] + [1.0 + s / SLIDE_RATE for s in range(1, 11)]
    fy, fxr = ref["Fy"], ref["Fx"]
    head = "| t | slide | ref F_z | ref F_x |" + "".join(" %s F_z | %s F_x | F_z diff | F_x diff |" % (n, n) for n, _ in runs)
    L = [head, "|" + "---|" * (4 + 4 * len(runs))]
    for t in times:
        rz, rx = np.interp(t, fy[:, 0], fy[:, 1]), np.interp(t, fxr[:, 0], fxr[:, 1])
        line = "| %.2f | %s | %.3f | %.3f |" % (t, "%.0f" % ((t - 1) * SLIDE_RATE) if t > 1 else "press", rz, rx)
        for _, r in runs:
            z, x = at(r, "fz", t), at(r, "fx", t)
            line += (" %.3f | %.3f | %+.1f %% | %+.1f %% |" % (z, x, 100 * (z / rz - 1), 100 * (x / rx - 1))
                     if z == z else " – | – | – | – |")
        L.append(line)
    return "\n".join(L)


def steady(r, t0=1.2, t1=1.8):
    m = (r["t"] >= t0) & (r["t"] <= t1)
    if m.sum() < 2:
        return None
    return dict(n=int(m.sum()), fz=r["fz"][m].mean(), fx=r["fx"][m].mean(),
                ratio=(r["fx"][m] / r["fz"][m]).mean(), ratio_min=(r["fx"][m] / r["fz"][m]).min(),
                ratio_max=(r["fx"][m] / r["fz"][m]).max(), fric=np.nanmean(r["fric"][m]),
                fric_max=np.nanmax(r["fric"][m]), slip=(r["slip"][m] == r["active"][m]).mean())


def deformed(ax, out, t_show=1.5):
    """the mesh's y = 0 faces at the stored step nearest t_show, the slave nodes in contact marked"""
    import h5py
    from matplotlib.collections import PolyCollection
    h = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        steps = sorted(f["steps"].keys())
        times = {r["step"]: float(r["time"]) for r in h}
        k = min(steps, key=lambda s: abs(times.get(str(int(s)), -9) - t_show))
        X = f["/mesh/coordinates"][:]
        H = f["/mesh/hexahedra"][:]
        s = f["steps"][k]
        x = X + s["displacement"][:]
        st = s["contact_status"][:]
    y0 = X[:, 1].min()
    quads = []
    for e in H:
        q = [n for n in e if abs(X[n, 1] - y0) < 1e-12]
        if len(q) == 4:
            quads.append(x[q][:, [0, 2]])
    ax.add_collection(PolyCollection(quads, facecolors="none", edgecolors="0.55", linewidths=0.3))
    m = (st > 0) & (np.abs(X[:, 1] - y0) < 1e-12)
    ax.plot(x[m, 0], x[m, 2], ".", ms=3, color="tab:orange", label="slave nodes in contact")
    t = times.get(str(int(k)), float("nan"))
    ax.set_xlim(x[m, 0].min() - 1.0, x[m, 0].max() + 1.0)
    ax.set_ylim(-2.2, 1.0)
    ax.set_aspect("equal")
    ax.set_title("t = %.2f (slide %.1f): y = 0 faces, deformed" % (t, (t - 1) * SLIDE_RATE), fontsize=9)
    ax.legend(fontsize=7, loc="lower right")


def figure(runs, ref, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(16, 4.6), gridspec_kw=dict(width_ratios=[1.2, 1, 1]))
    a.plot(ref["Fy"][:, 0], ref["Fy"][:, 1], "o", mfc="none", color="tab:blue", label="$F_z$ reference")
    a.plot(ref["Fx"][:, 0], ref["Fx"][:, 1], "o", mfc="none", color="tab:red", label="$F_x$ reference")
    styles = ["-", "--", ":", "-."]
    for k, (name, r) in enumerate(runs):
        ls = styles[k % len(styles)]
        a.plot(r["t"], r["fz"], ls, color="tab:blue", label="$F_z$ " + name)
        a.plot(r["t"], r["fx"], ls, color="tab:red", label="$F_x$ " + name)
        m = r["t"] > 1.0
        if m.any():
            b.plot((r["t"][m] - 1) * SLIDE_RATE, r["fx"][m] / r["fz"][m], ls, color="k", label="$F_x/F_z$ " + name)
            b.plot((r["t"][m] - 1) * SLIDE_RATE, r["fric"][m], ls, color="tab:green",
                   label="friction / normal, " + name)
    rm = ref["Fy"][:, 0] > 1.0
    tt = ref["Fy"][rm, 0]
    b.plot((tt - 1) * SLIDE_RATE, np.interp(tt, ref["Fx"][:, 0], ref["Fx"][:, 1]) / ref["Fy"][rm, 1], "o", mfc="none",
           color="k", label="$F_x/F_z$ reference")
    b.axhline(MU, color="gray", lw=0.8)
    b.text(9.0, MU - 0.03, "μ = 0.3", color="gray")
    a.set_xlabel("time (press 0 to 1, contact from 0.2; slide 10 (t − 1))")
    a.set_ylabel("die force per unit thickness (1e8)")
    a.grid(alpha=0.3)
    a.legend(fontsize=7, loc="upper left")
    b.set_xlabel("slide")
    b.set_ylabel("ratio")
    b.set_ylim(0.0, 0.5)
    b.grid(alpha=0.3)
    b.legend(fontsize=7, loc="lower left")
    try:
        deformed(c, runs[0][1]["out"])
    except (OSError, KeyError, ValueError) as e:
        c.set_axis_off()
        c.text(0.1, 0.5, "no fields: %s" % e, fontsize=8)
    fig.suptitle("Ironing, μ = 0.3: die forces against the reference (shallow ironing, Kratos Examples)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out")
    ap.add_argument("--label", default="this code")
    ap.add_argument("--thickness", default=None)
    ap.add_argument("--extra", action="append", default=[])
    ap.add_argument("--log")
    ap.add_argument("--reference", default=REF)
    ap.add_argument("--figure", default=FIG)
    ap.add_argument("--no-figure", action="store_true")
    a = ap.parse_args(argv)
    ref = reference(a.reference)
    runs = [(a.label, run(a.out, a.thickness))]
    for e in a.extra:
        p = e.split(":")
        runs.append((p[1] if len(p) > 1 else p[0], run(p[0], p[2] if len(p) > 2 else None)))
    print(table(runs, ref))
    print()
    for name, r in runs:
        s = steady(r)
        c = np.nanmax(np.abs(np.r_[r["cz"] - r["fz"], r["cx"] - r["fx"]]) / np.maximum(r["fz"].max(), 1e-30))
        print("%s (%s, T = %g): %d steps to t = %.4f, %d Newton iterations; contact resultant against the reactions: "
              "largest difference %.2e of the largest F_z" % (name, r["out"], r["T"], len(r["t"]), r["t"][-1], r["its"].sum(), c))
        if s:
            print("  steady slide (t 1.2 to 1.8, %d steps): F_z %.3f, F_x %.3f, F_x/F_z %.3f (%.3f to %.3f), friction/normal %.4f "
                  "(max %.4f; mu %.1f), all active nodes slipping in %.0f %% of the steps"
                  % (s["n"], s["fz"], s["fx"], s["ratio"], s["ratio_min"], s["ratio_max"], s["fric"], s["fric_max"], MU, 100 * s["slip"]))
    ls = logstats(a.log)
    if ls:
        print("log %s: %s; cuts %d%s" % (a.log, "done: %s steps, %s Newton iterations, %s cuts, %s s" % ls["done"] if ls["done"]
                                        else "stopped at step %s, time %s, %s s" % ls["last"], ls["cuts"],
                                        "; " + ls["error"].group(1)[:300] if ls["error"] else ""))
    if not a.no_figure:
        figure(runs, ref, a.figure)
        print("wrote %s" % os.path.relpath(a.figure, ROOT))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
