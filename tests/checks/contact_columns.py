"""contact_columns.py RUN HISTORY_COLUMNS PATH MU LABEL

history.csv of RUN must carry exactly the reaction columns HISTORY_COLUMNS (comma-separated) after
its five fixed columns, and last the column stage ("load" without stages; contact.csv too). contact.csv (one tool) must give: dx, dy, dz = the tool's piecewise-linear
PATH ("load,dx,dy,dz;..."), path_length = the length travelled along it, force = (fx, fy, fz) . dir
with dir the motion at load 1, force_normal and force_tangential the magnitudes of the normal and
tangential resultants for a tool whose normal is +-z at every node in contact (plane; or, for the
sphere, their sum of squares = |f|^2 as an upper-bound check), and with MU = 0 no sticking or
slipping nodes. Tolerance 1e-10 relative."""
import csv, math, sys

run, hcols, path, mu, label = sys.argv[1], sys.argv[2].split(","), sys.argv[3], float(sys.argv[4]), sys.argv[5]
h = list(csv.DictReader(open(f"{run}/history.csv")))
c = list(csv.DictReader(open(f"{run}/contact.csv")))
pts = [[float(x) for x in p.split(",")] for p in path.split(";")]
errs = []
fixed = ["step", "time", "newton_its", "residual_initial", "residual_final"]
if list(h[0].keys()) != fixed + hcols + ["stage"]:
    errs.append(f"history columns {list(h[0].keys())[5:]} != {hcols + ['stage']}")
if list(c[0].keys())[-1] != "stage" or any(r["stage"] != "load" for r in h + c):
    errs.append("contact.csv's last column is not stage, or a row's stage is not 'load'")


def at(lam):
    for (l0, *a), (l1, *b) in zip(pts, pts[1:]):
        if lam <= l1:
            s = (lam - l0) / (l1 - l0)
            plen = sum(math.dist(p[1:], q[1:]) for p, q in zip(pts, pts[1:]) if q[0] <= l0) + s * math.dist(a, b)
            return [x + s * (y - x) for x, y in zip(a, b)], plen
    return pts[-1][1:], sum(math.dist(p[1:], q[1:]) for p, q in zip(pts, pts[1:]))


d1 = pts[-1][1:]
nd = math.sqrt(sum(x * x for x in d1))
dirv = [x / nd for x in d1]
fmax = max(max(abs(float(r[k])) for k in ("fx", "fy", "fz")) for r in c) or 1.0
worst = 0.0
for r in c:
    t = float(r["time"])
    d, plen = at(t)
    worst = max(worst, max(abs(float(r[k]) - v) for k, v in zip(("dx", "dy", "dz"), d)) / nd, abs(float(r["path_length"]) - plen) / nd)
    f = [float(r[k]) for k in ("fx", "fy", "fz")]
    worst = max(worst, abs(float(r["force"]) - sum(a * b for a, b in zip(f, dirv))) / fmax)
    fn, ft = float(r["force_normal"]), float(r["force_tangential"])
    if "plane" in run or "drag" in run:
        worst = max(worst, abs(fn - abs(f[2])) / fmax, abs(ft - math.hypot(f[0], f[1])) / fmax)
    elif fn + ft < math.sqrt(sum(x * x for x in f)) * (1 - 1e-10):
        errs.append(f"step {r['step']}: |f| {math.sqrt(sum(x*x for x in f)):.6g} > force_normal + force_tangential")
    if mu == 0 and (int(r["stick"]) or int(r["slip"]) or ft > 1e-12 * fmax):
        errs.append(f"step {r['step']}: frictionless, yet stick {r['stick']} slip {r['slip']} force_tangential {ft:.3g}")
    if int(r["active"]) < int(r["stick"]) + int(r["slip"]):
        errs.append(f"step {r['step']}: active < stick + slip")
if worst > 1e-10:
    errs.append(f"largest relative error {worst:.2e}")
active = max(int(r["active"]) for r in c)
ok = not errs and active > 0
print(("ok" if ok else "not ok") + f" - result columns, {label}: reactions {','.join(hcols)}; tool displacement, path length, force vector and resultants over {len(c)} steps (largest error {worst:.1e}, up to {active} nodes pressed)" + ("" if ok else ": " + "; ".join(errs[:3])))
