#!/usr/bin/env python3
"""A picture of the deformed sheet coloured by a cell field (default: the equivalent plastic
strain), drawn with matplotlib from the HDF5 fields: the outer faces of the hexahedra, the quarter
model mirrored to the full sheet. For ParaView, see scripts/render.py.

usage: plot_sheet.py OUTDIR [picture.png] [--field plastic_strain] [--step last] [--quarter]"""
import argparse
import os
import sys

import h5py
import numpy as np

ap = argparse.ArgumentParser()
ap.add_argument("outdir")
ap.add_argument("png", nargs="?")
ap.add_argument("--field", default="plastic_strain")
ap.add_argument("--step", default="last")
ap.add_argument("--quarter", action="store_true", help="do not mirror the quarter model")
ap.add_argument("--title", default="")
a = ap.parse_args()
f = h5py.File(os.path.join(a.outdir, "fields.h5"), "r")
X, H = f["mesh/coordinates"][:], f["mesh/hexahedra"][:]
keys = sorted(f["steps"].keys())
g = f["steps"][keys[-1] if a.step == "last" else "%06d" % int(a.step)]
x = X + g["displacement"][:]
val = g[a.field][:]
# the bottom face of every hexahedron (nodes 0-3); the sheet seen from below shows the punch side
faces = H[:, [0, 1, 2, 3]]
polys, vals = [], []
mirrors = [(1, 1)] if a.quarter else [(1, 1), (-1, 1), (1, -1), (-1, -1)]
for sx, sy in mirrors:
    for fc, v in zip(faces, val):
        p = x[fc].copy()
        p[:, 0] *= sx
        p[:, 1] *= sy
        polys.append(p)
        vals.append(v)
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

fig = plt.figure(figsize=(8, 6))
ax = fig.add_subplot(111, projection="3d")
cmap = plt.get_cmap("jet")
vmin, vmax = float(np.min(vals)), float(np.max(vals))
col = Poly3DCollection(polys, facecolors=cmap((np.array(vals) - vmin) / max(vmax - vmin, 1e-30)), edgecolors="k", linewidths=0.1)
ax.add_collection3d(col)
lim = np.abs(x[:, :2]).max()
ax.set_xlim(-lim, lim)
ax.set_ylim(-lim, lim)
ax.set_zlim(x[:, 2].min() - 5, x[:, 2].max() + 5)
ax.set_box_aspect((1, 1, max(0.3, (x[:, 2].max() - x[:, 2].min() + 10) / (2 * lim))))
ax.view_init(elev=25, azim=-60)
ax.set_axis_off()
sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(vmin, vmax))
fig.colorbar(sm, ax=ax, shrink=0.6, label=a.field.replace("_", " "))
ax.set_title(a.title or f"{os.path.basename(os.path.normpath(a.outdir))}, load {float(g.attrs['time']):.3f}")
png = a.png or os.path.join(a.outdir, "sheet.png")
fig.savefig(png, dpi=110, bbox_inches="tight")
print(f"wrote {png}", file=sys.stderr)
