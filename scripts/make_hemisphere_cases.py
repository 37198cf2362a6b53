#!/usr/bin/env python3
"""Writes the hemispherical punch benchmark's options files under cases/:
hemisphere_{frictionless,friction}[_analytic][_refined|_fine|_xfine].opts.

The Coons cases build the tools as the method's paper did (scripts/coons_tools.py: punch from 3
Coons patches and a plane, die fillet from 1 Coons patch); the _analytic cases use a sphere and a
torus. Seed mesh: 301 hexahedra, one layer (the paper: 294); _refined: 3 layers, 12x the elements;
_fine: 4 layers, 32x; _xfine: 4 layers, 68x. The refined meshes give the contact penalties per
unit area (-contact_penalty_per_area), equal per unit area to the seed mesh's per-node values.
The Coons tools are the files cases/tools/hemisphere_{punch,die}_{coons,coons3}.tool; they are
written from scripts/coons_tools.py only when missing or with --coons-tools (its last printed digit
follows the platform's libm: the committed files keep the values the stored references were made
with).

  python3 scripts/make_hemisphere_cases.py [--coons-tools]"""
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
cases = os.path.join(here, "..", "cases")

HEAD = """# Hemispherical punch stretching (Lee, Wagoner & Nakamachi benchmark), {what}, quarter model,
# {mesh}, {tools}.
# Geometry (mm): punch radius 50.8, its pole touching the sheet's bottom face; die fillet radius
# 6.35 tangent to the die face at the clamp radius 59.18 (die opening 52.83, clearance 2.03);
# sheet 1.0 thick in 0 <= z <= 1, rim clamped. Material (MPa): E 69004, nu 0.3,
# Swift 589 (1e-4 + ep)^0.216. Punch travel 40. Written by scripts/make_hemisphere_cases.py.
"""
MESHES = {
    "": ("seed-size mesh (301 hexahedra, one layer)", 7, 18, 1),
    "_refined": ("refined mesh (3612 hexahedra, 3 layers)", 14, 36, 3),
    "_fine": ("fine mesh (9600 hexahedra, 4 layers)", 20, 50, 4),
    "_xfine": ("extra-fine mesh (20400 hexahedra, 4 layers)", 30, 70, 4),
}
COMMON = """-mesh_type blank
-blank_radius 59.18
-blank_thickness 1.0
-blank_core 0.4
-blank_core_cells {nc}
-blank_radial_cells {nr}
-blank_layers {nl}
-blank_quarter true
-material_E 69004
-material_nu 0.3
-material_hardening swift
-material_swift_K 589
-material_swift_eps0 1e-4
-material_swift_n 0.216
-bc_names clamp,symx,symy
-bc_clamp_set rim
-bc_clamp_components x,y,z
-bc_symx_set symx
-bc_symx_components x
-bc_symy_set symy
-bc_symy_components y
# contact: the bottom face on the punch, the top face on the die
-contact_set bottom,top
{penalty}-contact_friction {mu}
{stepping}-output_interval 4
-output_dir out/{name}
"""
ANALYTIC = """-tool_names punch,die
-tool_punch_motion 0,0,40
-tool_punch_patches 1
-tool_punch_patch0_type sphere
-tool_punch_patch0_center 0,0,-50.8
-tool_punch_patch0_radius 50.8
-tool_punch_patch0_axis 0,0,1
-tool_punch_patch0_ref 1,0,0
-tool_punch_patch0_range 0,90,-10,100
-tool_die_patches 1
-tool_die_patch0_type torus
-tool_die_patch0_center 0,0,7.35
-tool_die_patch0_axis 0,0,1
-tool_die_patch0_ref 1,0,0
-tool_die_patch0_major 59.18
-tool_die_patch0_minor 6.35
-tool_die_patch0_range -10,100,180,270
"""
# contact penalty: the paper's per-node values on the seed mesh; on the refined meshes the same
# stiffness per unit area, each node's penalties scaled by its tributary area (doc/contact.md):
# 1e5 and 5e3 divided by the seed's mean tributary area, 5489.82 mm2 / 668 slave nodes
SEED_AREA = 5489.821322 / 668
PENALTY_NODE = "-contact_penalty_normal 1e5\n-contact_penalty_tangential 5e3\n"
PENALTY_AREA = ("# penalties per unit area (N/mm3): the seed mesh's per-node values over its mean tributary area\n"
                f"-contact_penalty_per_area\n-contact_penalty_normal {1e5 / SEED_AREA:.5g}\n-contact_penalty_tangential {5e3 / SEED_AREA:.4g}\n")
# per mesh: on the extra-fine mesh a few steps take up to 19 Newton iterations; the increment
# grows again after steps of up to 10
EXTRA = {"_xfine": "# steps of up to 10 Newton iterations let the increment grow again after a cut\n-load_grow_its 10\n"}
# load stepping: increments from 1/40 of the travel growing by 1.5 up to 1/20 after steps of at
# most 5 Newton iterations, the linear extrapolation and the committed contact held on the
# frictionless tools in a step's first iteration (the code's defaults)
STEPPING = "-load_steps 40\n-load_dt_max 0.05\n"
# the Coons cases on the seed and refined meshes: 15 equal increments of the travel on the code's
# default stepping (the extrapolation predictor with its curvature term), the committed contact held
# on every tool in a step's first iteration with friction (the moving punch and the die at rest):
# 75 and 79 Newton iterations on the seed mesh (doc/performance.md, Newton iterations)
STEPPING_NEWTON = ("# 15 equal steps on the default stepping (doc/performance.md, Newton iterations)\n"
                   "-load_steps 15\n")
KEEP_ALL = "-newton_keep_contact all\n"
# Coons tools: the paper's construction with each punch patch split 3 x 3 (27 + 1 plane) and the
# die fillet in 4 sectors, so that the tool surfaces lie within 0.02 mm of the sphere and torus;
# the paper's own 3 + 1 and 1 patches (up to 0.52 mm off) are kept in hemisphere_*_coons3.opts
# The patches go to tool files under cases/tools/ (one per tool, the patch options without their
# prefix -tool_<t>_, doc/tools.md "Tool files"); the cases name them with -tool_<t>_file.


def tool_files(opts, tag, desc):
    """Splits coons_tools.py's options: each tool's patch options into cases/tools/hemisphere_<t>_<tag>.tool,
    the rest (names, motion) kept; returns the case's tool options."""
    keep, files = [], {}
    for line in opts.splitlines():
        key, _, val = line.partition(" ")
        t = key[len("-tool_"):].split("_", 1)
        if key.startswith("-tool_") and len(t) == 2 and t[1].startswith("patch"):
            files.setdefault(t[0], []).append(f"{t[1]} {val}")
        else:
            keep.append(line)
    for t, lines in files.items():
        rel = f"cases/tools/hemisphere_{t}_{tag}.tool"
        if os.path.exists(os.path.join(here, "..", rel)) and "--coons-tools" not in sys.argv:
            keep.append(f"-tool_{t}_file {rel}")
            continue
        with open(os.path.join(here, "..", rel), "w") as f:
            f.write(f"# hemispherical punch benchmark, the {t}: {desc}.\n# Written by scripts/make_hemisphere_cases.py (scripts/coons_tools.py).\n" + "\n".join(lines) + "\n")
        print("wrote " + rel)
        keep.append(f"-tool_{t}_file {rel}")
    return "\n".join(keep) + "\n"


coons = tool_files(subprocess.run([sys.executable, os.path.join(here, "coons_tools.py"), "--split", "3", "--die-sectors", "4"], check=True, capture_output=True, text=True).stdout,
                   "coons", "Coons patches as the method's paper built them, each punch patch split 3 x 3 (27 + 1 plane), the die fillet in 4 sectors")
coons3 = tool_files(subprocess.run([sys.executable, os.path.join(here, "coons_tools.py")], check=True, capture_output=True, text=True).stdout,
                    "coons3", "the paper's own Coons patches (punch 3 + 1 plane, die fillet 1)")
for fr, mu, what in (("frictionless", 0, "frictionless"), ("friction", 0.15, "Coulomb friction mu = 0.15")):
    for tl, tools, tdesc in (("", coons, "punch from 3 Coons patches (each split 3 x 3) + 1 plane, die fillet from 4 Coons patches"),
                             ("_coons3", coons3, "the paper's tools: punch from 3 Coons patches + 1 plane, die fillet from 1 Coons patch"),
                             ("_analytic", ANALYTIC, "analytic tools: sphere punch, torus die fillet")):
        for ms, (mdesc, nc, nr, nl) in MESHES.items():
            if tl == "_coons3" and ms:
                continue
            name = f"hemisphere_{fr}{tl}{ms}"
            newton = tl == "" and ms in ("", "_refined")
            stepping = (STEPPING_NEWTON + (KEEP_ALL if mu else "")) if newton else STEPPING
            text = HEAD.format(what=what, mesh=mdesc, tools=tdesc) + COMMON.format(nc=nc, nr=nr, nl=nl, mu=mu, name=name, penalty=PENALTY_AREA if ms else PENALTY_NODE, stepping=stepping) + EXTRA.get(ms, "") + tools
            with open(os.path.join(cases, name + ".opts"), "w") as f:
                f.write(text if text.endswith("\n") else text + "\n")
            print("wrote cases/" + name + ".opts")
