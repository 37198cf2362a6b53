#!/usr/bin/env python3
"""The NUMISHEET'93 square cup (mild steel, coarse) with the rigid and with the elastic blank holder:
draw-in, the holder's contact on the flange, the figure of doc/notes/elastic-holder.md.

usage: cup_elastic_holder.py [--rigid CASE] [--elastic CASE] [--extra LABEL=CASE ...] [--png PATH]
                             [--travels 0,5,15,25,40] [--plot-travels 15,40]

Reads out/<case>/ (contact.csv, fields.h5) and out/<case>.log of the two runs (defaults
numisheet93_cup_coarse and numisheet93_cup_coarse_elastic_holder, run as
  bin/atrito -options_file cases/<case>.opts > out/<case>.log
with a line "# wall time S s, exit RC" appended, as scripts/numisheet93.py writes it) and prints:
  * the draw-in DX, DY, DD at 15 and 40 mm of punch travel (scripts/numisheet93.py's measurement on
    the blank's nodes only: the plate's nodes at (75, 0), (0, 75), (75, 75) are left out);
  * steps, Newton iterations, cuts, wall time (the log);
  * the holder on the flange at a few punch travels (the output step nearest each): the number of
    the blank's top nodes pressed by the holder (contact_normal_force > 0 on the top nodes outside
    the rounded square of half side 40 in the current configuration, beyond the punch's walls at
    35), their largest and mean nodal force, the sum, and the holder's row of contact.csv (the rigid
    tool "holder"; the pair "ph" and the press's plane "holder" for the elastic holder);
  * the flange's thickness under the holder (the largest, at the nodes pressed), the plate's
    deflection (the spread of its bottom face's z displacement) and the press plane's nodes.
Draws the holder's nodal forces on the deformed blank's top face, one column per run (rigid, steel
plate, each --extra run), one row per travel of --plot-travels: doc/figures/elastic_holder.png.
"""
import argparse
import csv
import math
import os
import re
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
sys.path.insert(0, HERE)
from numisheet93 import drawin, run_info  # noqa: E402

T = 0.78
NBLANK = 1922          # the blank's nodes: ids 1..1922 in both meshes (31 x 31 x 2)
INNER = 40.0           # the flange: outside the rounded square of half side 40 (corner radius 15 about (25, 25))


def outside(xy, half=INNER, c0=25.0):
    """signed distance of points outside the rounded square of half side `half` (corner about (c0, c0))"""
    x, y = np.abs(xy[:, 0]), np.abs(xy[:, 1])
    r = half - c0
    dx, dy = np.maximum(x - c0, 0.0), np.maximum(y - c0, 0.0)
    corner = (x > c0) & (y > c0)
    return np.where(corner, np.hypot(dx, dy) - r, np.maximum(x, y) - half)


class Run:
    def __init__(self, case):
        self.case = case
        d = os.path.join(ROOT, "out", case)
        self.rows = list(csv.DictReader(open(os.path.join(d, "contact.csv"))))
        self.info = run_info(case)
        self.f = h5py.File(os.path.join(d, "fields.h5"), "r")
        self.X = self.f["mesh/coordinates"][:]
        self.ids = self.f["mesh/node_ids"][:]
        self.H = self.f["mesh/hexahedra"][:]
        self.blank = self.ids <= NBLANK
        self.top = self.blank & np.isclose(self.X[:, 2], T)
        self.bot = self.blank & np.isclose(self.X[:, 2], 0.0)
        self.plate = ~self.blank
        self.travel = {int(r["step"]): abs(float(r["travel"])) for r in self.rows if r["tool"] == "punch"}
        self.steps = sorted(int(k) for k in self.f["steps"].keys())

    def g(self, step):
        return self.f["steps"]["%06d" % step]

    def row(self, step, tool):
        for r in self.rows:
            if int(r["step"]) == step and r["tool"] == tool:
                return r
        return None

    def nearest(self, travel):
        cand = [s for s in self.steps if s in self.travel]
        return min(cand, key=lambda s: (abs(self.travel[s] - travel), -s))

    def drawin_at(self, target):
        steps = [s for s in self.steps if s in self.travel]
        h = [self.travel[s] for s in steps]
        Xb = self.X[self.blank]
        for a in range(len(steps) - 1):
            if h[a] <= target <= h[a + 1] and h[a + 1] > h[a]:
                w = (target - h[a]) / (h[a + 1] - h[a])
                D0 = drawin(Xb, self.g(steps[a])["displacement"][:][self.blank], T)
                D1 = drawin(Xb, self.g(steps[a + 1])["displacement"][:][self.blank], T)
                return {k: (1 - w) * D0[k] + w * D1[k] for k in D0}
        return None

    def holder(self, step):
        g = self.g(step)
        u = g["displacement"][:]
        x = self.X + u
        F = g["contact_normal_force"][:]
        flange = self.top & (outside(x[:, :2]) > 0)
        pressed = flange & (F > 0)
        Fp = F[pressed]
        # the flange's thickness at the pressed nodes: top node over its bottom node (same x, y in the reference)
        key = {(round(p[0], 6), round(p[1], 6)): i for i, p in enumerate(self.X) if self.bot[i]}
        thick = [x[i, 2] - x[key[(round(self.X[i, 0], 6), round(self.X[i, 1], 6))], 2] for i in np.where(pressed)[0]]
        out = dict(step=step, travel=self.travel.get(step, 0.0), n=int(pressed.sum()),
                   fmax=float(Fp.max()) if len(Fp) else 0.0, fmean=float(Fp.mean()) if len(Fp) else 0.0,
                   fsum=float(Fp.sum()), tmax=float(max(thick)) if thick else float("nan"),
                   n1=int((Fp > 1.0).sum()), x=x, F=F, pressed=pressed, flange=flange)
        # where it acts: the share on the sides (reference min(x, y) < 30, the straight flange) and
        # within 15 degrees of the sides' midpoints (the reference position's angle from the nearer
        # symmetry plane); the friction: the tangential forces' sum on the nodes pressed
        ref = self.X[pressed]
        tot = max(Fp.sum(), 1e-30)
        out["share_sides"] = float(Fp[np.minimum(ref[:, 0], ref[:, 1]) < 30.0].sum() / tot)
        ang = np.degrees(np.arctan2(np.minimum(ref[:, 0], ref[:, 1]), np.maximum(ref[:, 0], ref[:, 1])))
        out["share_mid15"] = float(Fp[ang < 15.0].sum() / tot)
        Ft = g["contact_tangential_force"][:][pressed]
        out["ft_sum"] = float(np.linalg.norm(Ft, axis=1).sum())
        out["ft_mid15"] = float(np.linalg.norm(Ft[ang < 15.0], axis=1).sum())
        # the share of the force on the nodes carrying the most: how many nodes carry half of it
        if len(Fp):
            s = np.sort(Fp)[::-1]
            out["n_half"] = int(np.searchsorted(np.cumsum(s), 0.5 * s.sum()) + 1)
        r = self.row(step, "ph") or self.row(step, "holder")
        out["csv_tool"] = r["tool"] if r else None
        out["csv_active"] = int(r["active"]) if r else 0
        out["csv_force"] = float(r["force"]) if r else 0.0
        out["csv_stick"], out["csv_slip"] = (int(r["stick"]), int(r["slip"])) if r else (0, 0)
        rh = self.row(step, "holder")
        out["holder_dz"] = float(rh["dz"]) if rh else 0.0
        out["holder_active"] = int(rh["active"]) if rh else 0
        if self.plate.any():
            pb = self.plate & np.isclose(self.X[:, 2], T)
            uz = u[pb, 2]
            out["plate_uz"] = (float(uz.min()), float(uz.max()))
            pt = self.plate & (self.X[:, 2] > self.X[:, 2].max() - 1e-6)
            out["plate_top_pressed"] = int((F[pt] > 0).sum())
            out["plate_top_n"] = int(pt.sum())
        return out

    def punch_force_max(self):
        return max(abs(float(r["force_full"])) for r in self.rows if r["tool"] == "punch") / 1000.0


def plot(runs, travels, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import LogNorm
    fig, axs = plt.subplots(len(travels), len(runs), figsize=(4.3 * len(runs), 4.4 * len(travels)), squeeze=False)
    norm = LogNorm(1.0, 400.0)
    for j, (label, R) in enumerate(runs):
        faces = np.array([hx[4:8] for hx in R.H if R.blank[hx[0]]])   # the blank's top faces
        for i, t in enumerate(travels):
            s = R.nearest(t)
            h = R.holder(s)
            ax = axs[i, j]
            x = h["x"]
            ax.add_collection(PolyCollection([x[f, :2] for f in faces], facecolors="0.88", edgecolors="0.7", linewidths=0.2))
            th = np.linspace(0, 0.5 * math.pi, 50)
            ax.plot(np.r_[45, 45, 25 + 20 * np.cos(th), 0], np.r_[0, 25, 25 + 20 * np.sin(th), 45], "r-", lw=0.8)
            ax.plot([75, 75, 0], [0, 75, 75], "k:", lw=0.6)
            p = np.where(h["pressed"])[0]
            p = p[np.argsort(h["F"][p])]
            sc = ax.scatter(x[p, 0], x[p, 1], c=np.maximum(h["F"][p], 1.0), s=3 + 0.25 * h["F"][p], cmap="viridis",
                            norm=norm, edgecolors="k", linewidths=0.2, zorder=3)
            ax.set_aspect("equal")
            ax.set_xlim(0, 77)
            ax.set_ylim(0, 77)
            ax.set_title("%s, travel %.1f mm\n%d nodes pressed (half the force on %s)\nlargest %.0f N, mean %.1f N"
                         % (label, h["travel"], h["n"], h.get("n_half", "-"), h["fmax"], h["fmean"]), fontsize=8.5)
            ax.tick_params(labelsize=7)
            if i == len(travels) - 1:
                ax.set_xlabel("x (mm)", fontsize=8)
            if j == 0:
                ax.set_ylabel("y (mm)", fontsize=8)
    fig.colorbar(sc, ax=axs, shrink=0.5, label="holder's normal force on the blank's top node (N)")
    fig.suptitle("NUMISHEET'93 square cup, mild steel, coarse, quarter model: where the holder's 4.9 kN rests on the flange\n"
                 "(blank's top face deformed, grey; red: the die face's inner edge; dotted: the blank's initial outline;\n"
                 "dots: nodes pressed by the holder, colour and size the nodal force)", fontsize=9)
    fig.savefig(png, dpi=110, bbox_inches="tight")
    print("wrote %s" % png, file=sys.stderr)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rigid", default="numisheet93_cup_coarse")
    ap.add_argument("--elastic", default="numisheet93_cup_coarse_elastic_holder")
    ap.add_argument("--png", default=os.path.join(ROOT, "doc", "figures", "elastic_holder.png"))
    ap.add_argument("--travels", default="0,5,15,25,40")
    ap.add_argument("--plot-travels", default="15,40")
    ap.add_argument("--extra", action="append", default=[], metavar="LABEL=CASE",
                    help="a further run to tabulate and draw (a diagnostic variant), e.g. 'plate E 2060=CASE'")
    a = ap.parse_args()
    runs = [("rigid holder", Run(a.rigid)), ("steel plate", Run(a.elastic))]
    runs += [(e.split("=")[0], Run(e.split("=")[1])) for e in a.extra]
    travels = [float(v) for v in a.travels.split(",")]
    print("| | %s |" % " | ".join(lab for lab, _ in runs))
    print("|---|%s" % ("---|" * len(runs)))
    D = {lab: {t: R.drawin_at(t) for t in (15.0, 40.0)} for lab, R in runs}
    for t in (15.0, 40.0):
        for k in ("DX", "DY", "DD"):
            print("| %s at %g mm | %s |" % (k, t, " | ".join(
                "%.2f" % D[lab][t][k] if D[lab][t] else "-" for lab, _ in runs)))
    for key in ("steps", "its", "cuts", "wall", "status"):
        print("| %s | %s |" % (key, " | ".join(str(R.info.get(key)) if R.info else "-" for _, R in runs)))
    print("| largest punch force (kN, whole cup) | %s |" % " | ".join("%.2f" % R.punch_force_max() for _, R in runs))
    print()
    print("| holder | travel (mm) | step | nodes pressed (F > 0; > 1 N) | nodes carrying half | largest F (N) | mean F (N) | sum (N) | share on the sides; within 15 deg of their midpoints | friction (N): all; within 15 deg | contact.csv row: active, stick, slip, force | flange thickness, largest (mm) | press plane dz (mm) | plate bottom uz (mm) | plate top nodes pressed |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for lab, R in runs:
        for t in travels:
            s = R.nearest(t)
            h = R.holder(s)
            print("| %s | %.2f | %d | %d; %d | %s | %.1f | %.2f | %.1f | %.2f; %.2f | %.0f; %.0f | %s: %d, %d, %d, %.1f | %.3f | %.3f | %s | %s |" % (
                lab, h["travel"], s, h["n"], h["n1"], h.get("n_half", "-"), h["fmax"], h["fmean"], h["fsum"],
                h["share_sides"], h["share_mid15"], h["ft_sum"], h["ft_mid15"],
                h["csv_tool"], h["csv_active"], h["csv_stick"], h["csv_slip"], h["csv_force"], h["tmax"],
                h["holder_dz"], "%.4f to %.4f" % h["plate_uz"] if "plate_uz" in h else "-",
                "%d of %d" % (h["plate_top_pressed"], h["plate_top_n"]) if "plate_uz" in h else "-"))
    plot(runs, [float(v) for v in a.plot_travels.split(",")], a.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
