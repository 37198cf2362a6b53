#!/usr/bin/env bash
# Contact between deformable bodies (-pair_names; src/contact/pair.c):
#   1. the patch test (cases/pair_patch.opts: two blocks, non-matching meshes 3x3 on 4x4): the
#      resultant equals the reactions; the single pass's stress spread held at what it is (node to
#      surface does not pass this test: doc/contact.md), the two-pass option with its constraints
#      met to 1e-12 (its augmented Lagrangian) uniform to 1e-8 and equal to the closed form; 1 and
#      2 ranks agree (the master faces on the other rank there);
#   2. the exact tangent: -snes_test_jacobian without friction, in stick and in slip;
#   3. sliding: Coulomb's F_T = mu F_N for a block that slips on the other;
#   4. restart on another number of ranks reproduces the uninterrupted run;
#   5. Hertz between two elastic cylinders' worth (cases/pair_hertz.opts, plane strain): half-width
#      and peak pressure within 2 % of the closed form (tests/checks/hertz_pair.py), 1 and 2 ranks;
#   6. the rigid limit: the seed benchmark with the punch and the die as elastic bodies 1e3 times
#      the sheet's modulus (cases/hemisphere_bodies_frictionless.opts) against the rigid tools over
#      the first 3 of its 15 steps (the whole study: scripts/rigid_limit.py, doc/notes/rigid-limit.md).
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out pairs)
PATCH="-options_file cases/pair_patch.opts -output_interval 1"
# the upper block sheared as it is pressed: its top moved in x, y and z, the rollers on the lower block only
SLIDE="-options_file cases/pair_patch.opts -output_interval 0 -bc_symx_set lower_xmin -bc_symy_set lower_ymin -bc_top_components x,y,z -bc_top_values 0.03,0.01,-0.01 -load_steps 4"

# 1. patch test
# shellcheck disable=SC2086
TWO="-pair_p_two_pass -pair_p_augmented_tol 1e-12"
# shellcheck disable=SC2086
atrito 1 patch1 $PATCH && atrito 2 patch2 $PATCH && atrito 1 patch2p $PATCH $TWO && atrito 2 patch2p2 $PATCH $TWO && {
  compare "$OUT/patch1/history.csv" "$OUT/patch2/history.csv" 8 "patch test, np=1 and np=2: history.csv"
  compare "$OUT/patch1/contact.csv" "$OUT/patch2/contact.csv" 8 "patch test, np=1 and np=2: contact.csv"
  compare "$OUT/patch2p/history.csv" "$OUT/patch2p2/history.csv" 8 "patch test (two-pass), np=1 and np=2: history.csv (the penetrations, below 1e-12, are round-off)"
  $PY - "$OUT/patch1" "$OUT/patch2p" <<'PY'
import csv, sys, h5py, numpy as np
fail = 0
# the single pass is held at what it gives (0.341); the two-pass one with its constraints met to
# 1e-12 (augmented) makes both bodies' interfaces coincide: the exact uniform state
for d, label, bound in ((sys.argv[1], "single pass", 0.35), (sys.argv[2], "two-pass", 1e-8)):
    h = list(csv.DictReader(open(d + "/history.csv")))[-1]
    c = [r for r in csv.DictReader(open(d + "/contact.csv"))][-1]
    top, base, fz = -float(h["top_fz"]), float(h["base_fz"]), float(c["fz"])
    e = max(abs(fz - top), abs(fz - base)) / top
    # the force lies below the rigid limit 10.152 (finite strain, g = 0) by the penalty's compliance
    ok = e < 1e-6 and 7.5 < top < 10.152
    fail += not ok
    print(("ok" if ok else "not ok") + f" - patch test, {label}: the pair's resultant {fz:.6f} equals the reactions {top:.6f}, {base:.6f} (relative {e:.1e} < 1e-6; between 7.5 and the rigid limit 10.152)")
    f = h5py.File(d + "/fields.h5", "r")
    vm = np.array(f["steps"][sorted(f["steps"].keys())[-1]]["von_mises"])
    s = (vm.max() - vm.min()) / vm.mean()
    ok = s < bound
    fail += not ok
    print(("ok" if ok else "not ok") + f" - patch test, {label}: the cells' von Mises stress spreads by {s:.3g} of its mean (uniform in the exact solution; below {bound:g})")
    if bound < 1e-6:  # the closed form: Hencky, stretch 0.99, Cauchy |sigma_zz| = E |ln 0.99| / 0.99^(1 - 2 nu)
        exact = 1000 * -np.log(0.99) / 0.99 ** 0.4
        e = abs(vm.mean() / exact - 1)
        ok = e < 1e-6
        fail += not ok
        print(("ok" if ok else "not ok") + f" - patch test, {label}: von Mises {vm.mean():.8f}, the closed form {exact:.8f} (relative {e:.1e} < 1e-6)")
sys.exit(1 if fail else 0)
PY
}

# 1b. two bodies, two materials: the upper block 100 times stiffer (-body_names); uniaxial stress,
# each block's mean stress against the closed form (equal forces: E1 ln l1 / l1 = E2 ln l2 / l2 with
# l1 + l2 = 1.98 on halves 0.5 high; the penalty's penetration is below 1e-8 with the two-pass
# augmentation). (The bodies' lateral strains differ, so the stress is not uniform at the edges.)
# shellcheck disable=SC2086
atrito 1 bodies $PATCH $TWO -pair_p_augmented_tol 1e-8 -body_names up -body_up_set UPPER -body_up_material_E 1e5 && $PY - "$OUT/bodies" <<'PY'
import sys, h5py, numpy as np
E1, E2, nu = 1000.0, 1e5, 0.3
g = lambda l: E1 * np.log(l) / l - E2 * np.log(1.98 - l) / (1.98 - l)
a, b = 0.97, 0.99999
for _ in range(200):  # bisection
    m = 0.5 * (a + b)
    a, b = (m, b) if g(a) * g(m) > 0 else (a, m)
l1 = 0.5 * (a + b); l2 = 1.98 - l1
exact = (E1 * -np.log(l1) / l1 ** (1 - 2 * nu), E2 * -np.log(l2) / l2 ** (1 - 2 * nu))
f = h5py.File(sys.argv[1] + "/fields.h5", "r")
vm = np.array(f["steps"][sorted(f["steps"].keys())[-1]]["von_mises"])
fail = 0
for name, cells, ex in (("lower (E 1000)", vm[:32], exact[0]), ("upper (E 1e5)", vm[32:], exact[1])):
    e = abs(cells.mean() / ex - 1)
    ok = e < 1e-4
    fail += not ok
    print(("ok" if ok else "not ok") + f" - two bodies: the {name} block's mean von Mises stress {cells.mean():.6f}, the closed form {ex:.6f} (relative {e:.1e} < 1e-4)")
sys.exit(1 if fail else 0)
PY

# 1c. bodies from a Gmsh file's physical volumes (tests/data/two_bodies.msh: two hexahedra,
# "soft" and "stiff"): E 1000 by default with the body "stiff" at 2000, or E 2000 by default with
# the body "soft" at 1000, give the same run; the uniform E 1000 another
G="-mesh_file tests/data/two_bodies.msh -bc_names fix,pull -bc_fix_set left -bc_pull_set right -bc_fix_components x,y,z -bc_pull_components x -bc_pull_values 0.0002 -load_steps 1 -output_interval 0 -material_hardening linear -material_yield 1e9"
EL="-material_hardening linear -material_yield 1e9"
# shellcheck disable=SC2086
atrito 1 gmsh_a $G -material_E 1000 -body_names b -body_b_set stiff -body_b_material_E 2000 $(echo $EL | sed 's/-material/-body_b_material/g') &&
  atrito 2 gmsh_b $G -material_E 2000 -body_names b -body_b_set soft -body_b_material_E 1000 $(echo $EL | sed 's/-material/-body_b_material/g') &&
  atrito 1 gmsh_u $G -material_E 1000 && {
  compare "$OUT/gmsh_a/history.csv" "$OUT/gmsh_b/history.csv" 10 "bodies from Gmsh physical volumes: the stiff one set, or the soft one (np=2), the same run"
  $PY - "$OUT/gmsh_a/history.csv" "$OUT/gmsh_u/history.csv" <<'PY'
import csv, sys
a, u = (float(list(csv.DictReader(open(f)))[-1]["pull_fx"]) for f in sys.argv[1:3])
ok = a / u > 1.2
print(("ok" if ok else "not ok") + f" - bodies from Gmsh physical volumes: the stiff body raises the pull's reaction {a / u:.4f} times (> 1.2) over the uniform material")
sys.exit(0 if ok else 1)
PY
}

# 2. the tangent
# shellcheck disable=SC2086
atrito 1 jac0 $SLIDE -pair_p_friction 0 -snes_test_jacobian && pycheck snes_test_jacobian "$OUT/jac0.log" 6 1e-6 "contact pair without friction"
# shellcheck disable=SC2086
atrito 1 jac_stick $SLIDE -pair_p_friction 2 -snes_test_jacobian -output_interval 1 &&
  pycheck snes_test_jacobian "$OUT/jac_stick.log" 6 1e-6 "contact pair, mu = 2 (stick and slip)" --contact "$OUT/jac_stick"
# shellcheck disable=SC2086
atrito 2 jac_slip $SLIDE -pair_p_friction 0.3 -snes_test_jacobian && pycheck snes_test_jacobian "$OUT/jac_slip.log" 6 1e-6 "contact pair, mu = 0.3 (slip; np=2)"

# 2b. the smoothed master (-pair_p_smooth, normals held within an iteration): the tangent in
# sliding (the sheared block's corner normals differ; the curved face's derivatives are checked in
# tests/test_nts.c), and the two-pass patch test with the normals converged to 1e-10
# shellcheck disable=SC2086
atrito 1 jac_smooth $SLIDE -pair_p_friction 0.3 -pair_p_smooth -snes_test_jacobian && pycheck snes_test_jacobian "$OUT/jac_smooth.log" 6 1e-6 "contact pair with the smoothed master, slip"
# shellcheck disable=SC2086
atrito 1 patch_smooth $PATCH $TWO -pair_p_smooth -pair_p_smooth_tol 1e-10 && $PY - "$OUT/patch_smooth/fields.h5" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
vm = np.array(f["steps"][sorted(f["steps"].keys())[-1]]["von_mises"])
s = (vm.max() - vm.min()) / vm.mean()
print(("ok" if s < 1e-8 else "not ok") + f" - patch test, two-pass with the smoothed master (normals to 1e-10): spread {s:.2g} (< 1e-8)")
sys.exit(0 if s < 1e-8 else 1)
PY

# 3. Coulomb: every pressed node slips, F_T = mu F_N
# shellcheck disable=SC2086
atrito 1 slide1 $SLIDE -pair_p_friction 0.3 && atrito 2 slide2 $SLIDE -pair_p_friction 0.3 && {
  compare "$OUT/slide1/contact.csv" "$OUT/slide2/contact.csv" 8 "sliding, np=1 and np=2: contact.csv"
  $PY - "$OUT/slide1/contact.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
e = max(abs(float(r["force_tangential"]) / float(r["force_normal"]) - 0.3) for r in rows)
allslip = all(int(r["slip"]) == int(r["active"]) > 0 for r in rows)
ok = allslip and e < 1e-8
print(("ok" if ok else "not ok") + f" - sliding block: every pressed node slips ({allslip}), F_T / F_N = mu = 0.3 to {e:.1e} (< 1e-8)")
sys.exit(0 if ok else 1)
PY
}

# 4. restart: stopped after 3 steps at np=1, restarted at np=2
# shellcheck disable=SC2086
atrito_rc 1 rst $SLIDE -pair_p_friction 0.3 -load_steps 8 -checkpoint_interval 2 -load_max_steps 3 # (stops with an error by design)
atrito 2 rst $SLIDE -pair_p_friction 0.3 -load_steps 8 -checkpoint_interval 2 -restart "$OUT/rst/checkpoint.h5" &&
  atrito 1 rst_ref $SLIDE -pair_p_friction 0.3 -load_steps 8 &&
  compare "$OUT/rst_ref/contact.csv" "$OUT/rst/contact.csv" 8 "contact pair restarted from step 2 on 2 ranks: contact.csv"

# 5. Hertz
atrito 1 hertz1 -options_file cases/pair_hertz.opts && pycheck hertz_pair "$OUT/hertz1" --tol 0.02 --quiet
atrito 2 hertz2 -options_file cases/pair_hertz.opts && compare "$OUT/hertz1/contact.csv" "$OUT/hertz2/contact.csv" 8 "Hertz pair, np=1 and np=2: contact.csv" &&
  $PY - "$OUT/hertz2/fields.h5" cases/meshes/pair_hertz.inp <<'PY'
# both surfaces' normal forces in the node fields: the master nodes' (the slave nodes' forces on
# their faces, per vertex, on the vertex's mean normal) sum to the slave nodes' (2 ranks)
import re, sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
k = sorted(f["steps"].keys())[-1]
fn = np.array(f["steps"][k]["contact_normal_force"]).ravel()
ids = np.array(f["mesh/node_ids"]).ravel()
txt = open(sys.argv[2]).read()
def nset(name):
    m = re.search(r"\*NSET,\s*NSET=%s\s*\n(.*?)(?=\n\*)" % name, txt, re.S | re.I)
    return {int(t) for t in re.split(r"[,\s]+", m.group(1).strip()) if t}
S, M = nset("block_top"), nset("cyl_surface")
fs = fn[np.array([i in S for i in ids])].sum()
fm = fn[np.array([i in M for i in ids])].sum()
e = abs(fm / fs - 1)
print(("ok" if e < 1e-4 else "not ok") + f" - Hertz pair: the master surface's normal forces sum to {fm:.6f}, the slave's to {fs:.6f} (relative {e:.1e} < 1e-4)")
sys.exit(0 if e < 1e-4 else 1)
PY

# 6. the rigid limit, the first 8 mm in the benchmark's increments of 2.67 mm
atrito 1 rl_rigid -options_file cases/hemisphere_frictionless.opts -tool_punch_motion 0,0,8 -load_steps 3 -output_interval 0 &&
  atrito 1 rl_bodies -options_file cases/hemisphere_bodies_frictionless.opts -bc_drive_values 0,0,8 -load_steps 3 -output_interval 0 &&
  $PY - "$OUT/rl_rigid/contact.csv" "$OUT/rl_bodies/contact.csv" <<'PY'
import csv, sys
rig = [float(r["force_full"]) for r in csv.DictReader(open(sys.argv[1])) if r["tool"] == "punch"]
bod = [4 * float(r["fz"]) for r in csv.DictReader(open(sys.argv[2])) if r["tool"] == "pp"]
e = max(abs(b / a - 1) for a, b in zip(rig, bod))
ok = len(rig) == len(bod) == 3 and e < 5e-3
print(("ok" if ok else "not ok") + f" - rigid limit: punch force of elastic punch and die (1e3 E) against the rigid tools over {len(bod)} steps to 8 mm: largest difference {100 * e:.3f} % (< 0.5 %; the faceted punch's own)")
sys.exit(0 if ok else 1)
PY
