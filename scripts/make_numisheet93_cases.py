#!/usr/bin/env python3
"""Writes the NUMISHEET'93 benchmark inputs: the blank meshes (cases/sheets/*.inp), the tools
(cases/tools/numisheet93_*.tool, analytic patches) and the cases (cases/numisheet93_*.opts).

usage: make_numisheet93_cases.py
Geometry and data: doc/forming.md (the specification tables and their sources). Frame: x (and y
for the cup) in the sheet's plane from the symmetry plane(s), z up; the blank in 0 <= z <= t on
the die's face z = 0; the punch and the blank holder above it, the punch moving down (-z).

Two forms of every case:
  numisheet93_<b>_<mesh>.opts       the process of the benchmark: stages (close, draw, release,
                                    springback), the holder driven by its force, contact per tool;
  numisheet93_<b>_<mesh>_gap.opts   with the options available before those: the holder fixed at
                                    a gap equal to the sheet's thickness, one contact set and one
                                    friction coefficient for all tools, no stages (the drawing only);
  numisheet93_cup_<mesh>_gap110.opts  the same with the holder at a gap of 1.1 t.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
CASES = os.path.join(ROOT, "cases")
TOOLS = os.path.join(CASES, "tools")
SHEETS = os.path.join(CASES, "sheets")

# ---------------------------------------------------------------- data (doc/forming.md)
MILD = dict(E=206000.0, nu=0.3, K=565.32, eps0=0.007117, n=0.2589, r0=1.79, r45=1.51, r90=2.27)
U = dict(t=0.78, half_length=175.0, width=35.0, punch_half=35.0, punch_r=5.0, die_half=36.5,
         die_r=5.0, stroke=70.0, bhf=2450.0, mu=0.144)
CUP = dict(t=0.78, half=75.0, punch_half=35.0, punch_corner=10.0, punch_r=8.0, die_half=37.0,
           die_corner=12.0, die_r=8.0, stroke=40.0, bhf=19600.0, mu=0.144)
# The square cup in aluminium, the material of the published draw-in ([D]): t = 0.81 mm, E = 70 GPa,
# nu = 0.3 and mu = 0.162 as [D] (71 GPa and nu = 0.33 are also quoted in the literature); the Swift
# curve and the r-values as commonly reproduced from the specification of [M] (M-dagger: to be
# checked against [M]). The tools are the mild steel's, the punch's head and the holder's face on the
# thicker sheet's top face z = t.
# Its yield function: Barlat 1991 with the exponent of face-centred cubic metals, 8 (yld91,
# doc/materials.md), fitted to the same r-values: Hill 1948 with r < 1 puts the equibiaxial yield
# stress at 0.92 of the uniaxial one, below what aluminium alloys show; Barlat's at 0.95.
ALU = dict(E=70000.0, nu=0.3, K=576.79, eps0=0.01658, n=0.3593, r0=0.71, r45=0.58, r90=0.70, yld91=8)
CUP_AL = dict(CUP, t=0.81, mu=0.162)
# the cup's variants: tag (file names numisheet93_<tag>_*), geometry and process, material, its name
CUPS = {"cup": (CUP, MILD, "mild steel"), "cup_al": (CUP_AL, ALU, "aluminium")}
# Contact of the fixed-gap variants (*_gap.opts, the runs of doc/notes/forming-log.md's "Status" before the
# process cases): penalties per unit area and the augmented Lagrangian holding the penetration below 0.01 mm
# (1.3 % of the thickness), its multipliers to 20 % (with 1 %, the default, the U-channel's updates
# stall near 8 mm of stroke). The U-channel needs a soft penalty, 100 N/mm^3: with the strip's tiny
# bending stiffness a stiffer one makes the contact status of the web's nodes on the flat punch cycle
# from one Newton iteration to the next; the cup runs with 1000 N/mm^3. The search distance covers
# the whole tools: with the default (5 % of the largest tool box) a node over the die's cavity that is
# too far from its shoulder and walls is paired with the edge of the die's face, whose plane then
# acts as if it extended over the cavity. doc/notes/forming-log.md. The process cases give none of these: the
# contact sets and the friction only, on the code's defaults (doc/contact.md, Contact without tuning).
def contact(kn):
    return ["-contact_penalty_per_area", "-contact_penalty_normal %g" % kn, "-contact_penalty_tangential %g" % (kn / 10),
            "-contact_augmented", "-contact_augmented_tol 0.01", "-contact_augmented_multiplier_tol 0.2",
            "-contact_search_distance 300"]


MESHES = {"uchannel": {"coarse": 140, "fine": 350, "xfine": 700}, "cup": {"coarse": 30, "fine": 60}}


def fmt(v):
    return ",".join("%.10g" % x for x in v)


# ---------------------------------------------------------------- blank meshes (.inp)
def write_inp(path, title, nx, ny, lx, ly, t, extra_sets):
    """nx x ny x 1 hexahedra on [0,lx] x [0,ly] x [0,t]; node sets by predicates on (i, j, k)."""
    def nid(i, j, k):
        return 1 + i + (nx + 1) * (j + (ny + 1) * k)
    with open(path, "w") as f:
        f.write("** %s\n** written by scripts/make_numisheet93_cases.py\n*NODE\n" % title)
        for k in range(2):
            for j in range(ny + 1):
                for i in range(nx + 1):
                    f.write("%d, %.10g, %.10g, %.10g\n" % (nid(i, j, k), lx * i / nx, ly * j / ny, t * k))
        f.write("*ELEMENT, TYPE=C3D8, ELSET=blank\n")
        e = 1
        for j in range(ny):
            for i in range(nx):
                n = [nid(i, j, 0), nid(i + 1, j, 0), nid(i + 1, j + 1, 0), nid(i, j + 1, 0)]
                n += [nid(i, j, 1), nid(i + 1, j, 1), nid(i + 1, j + 1, 1), nid(i, j + 1, 1)]
                f.write("%d, %s\n" % (e, ", ".join(map(str, n))))
                e += 1
        sets = {"top": lambda i, j, k: k == 1, "bottom": lambda i, j, k: k == 0}
        sets.update(extra_sets(nx, ny))
        for name, pred in sets.items():
            ids = [nid(i, j, k) for k in range(2) for j in range(ny + 1) for i in range(nx + 1) if pred(i, j, k)]
            f.write("*NSET, NSET=%s\n" % name)
            for a in range(0, len(ids), 16):
                f.write(", ".join(map(str, ids[a:a + 16])) + "\n")


def uchannel_mesh(level):
    nx = MESHES["uchannel"][level]
    h = U["half_length"] / nx
    path = os.path.join(SHEETS, "numisheet93_uchannel_%s.inp" % level)
    write_inp(path, "NUMISHEET'93 U-channel, half strip %g x %g x %g, %d x 1 x 1 hexahedra (plane strain)"
              % (U["half_length"], h, U["t"], nx), nx, 1, U["half_length"], h, U["t"],
              lambda nx, ny: {"symx": lambda i, j, k: i == 0,
                              "sides": lambda i, j, k: True,
                              "pin": lambda i, j, k: i == 0 and k == 0,
                              "end": lambda i, j, k: i == nx})
    return path, h


def cup_mesh(level, tag="cup"):
    C = CUPS[tag][0]
    n = MESHES["cup"][level]
    path = os.path.join(SHEETS, "numisheet93_%s_%s.inp" % (tag, level))
    write_inp(path, "NUMISHEET'93 square cup, quarter blank %g x %g x %g, %d x %d x 1 hexahedra"
              % (C["half"], C["half"], C["t"], n, n), n, n, C["half"], C["half"], C["t"],
              lambda nx, ny: {"symx": lambda i, j, k: i == 0,
                              "symy": lambda i, j, k: j == 0,
                              "pin": lambda i, j, k: i == 0 and j == 0 and k == 0,
                              "rim": lambda i, j, k: i == nx or j == ny})
    return path


# ---------------------------------------------------------------- tool files (.tool)
class ToolFile:
    def __init__(self, comment):
        self.comment, self.patches = comment, []

    def plane(self, origin, e1, e2, rng, sense=1):
        self.patches.append([("type", "plane"), ("origin", fmt(origin)), ("e1", fmt(e1)), ("e2", fmt(e2)),
                             ("range", fmt(rng))] + ([("sense", "-1")] if sense < 0 else []))

    def cylinder(self, center, axis, ref, radius, rng, sense=1):
        self.patches.append([("type", "cylinder"), ("center", fmt(center)), ("axis", fmt(axis)), ("ref", fmt(ref)),
                             ("radius", "%.10g" % radius), ("range", fmt(rng))] + ([("sense", "-1")] if sense < 0 else []))

    def torus(self, center, axis, ref, major, minor, rng, sense=1):
        self.patches.append([("type", "torus"), ("center", fmt(center)), ("axis", fmt(axis)), ("ref", fmt(ref)),
                             ("major", "%.10g" % major), ("minor", "%.10g" % minor), ("range", fmt(rng))]
                            + ([("sense", "-1")] if sense < 0 else []))

    def coons(self, curves, sense=1):
        """curves: bottom, top, left, right as ("line", a, b) or ("arc", a, b, c)."""
        p = [("type", "coons")]
        for side, c in zip(("bottom", "top", "left", "right"), curves):
            p += [(side + "_type", c[0]), (side + "_points", fmt([x for pt in c[1:] for x in pt]))]
        self.patches.append(p + ([("sense", "-1")] if sense < 0 else []))

    def write(self, path):
        with open(path, "w") as f:
            for line in self.comment.splitlines():
                f.write("# %s\n" % line)
            f.write("patches %d\n" % len(self.patches))
            for j, p in enumerate(self.patches):
                for k, v in p:
                    f.write("patch%d_%s %s\n" % (j, k, v))


def uchannel_tools():
    t, pr, dr = U["t"], U["punch_r"], U["die_r"]
    a, d = U["punch_half"], U["die_half"]
    Y0, Y1 = -10.0, 20.0  # the strip (width <= 10) lies well inside the tools' extent along y
    L = U["half_length"] + 40.0
    # punch: flat head z = t for x <= a - pr, corner cylinder radius pr, wall x = a; normals outwards
    p = ToolFile("NUMISHEET'93 2D draw bending: punch (half), head on the sheet's top face z = t at load 0,\n"
                 "width %g (half %g), corner radius %g; written by scripts/make_numisheet93_cases.py" % (2 * a, a, pr))
    p.plane([-5, Y0, t], [0, 1, 0], [1, 0, 0], [0, Y1 - Y0, 0, a - pr + 5])             # -z
    p.cylinder([a - pr, 0, t + pr], [0, -1, 0], [0, 0, -1], pr, [0, 90, -Y1, -Y0])    # from -z to +x
    p.plane([a, Y0, t + pr], [0, 1, 0], [0, 0, 1], [0, Y1 - Y0, 0, 100])                # +x
    p.write(os.path.join(TOOLS, "numisheet93_uchannel_punch.tool"))
    # die: face z = 0 for x >= d + dr, shoulder cylinder radius dr, wall x = d facing the cavity (-x)
    q = ToolFile("NUMISHEET'93 2D draw bending: die (half), face z = 0, opening %g (half %g),\n"
                 "shoulder radius %g; written by scripts/make_numisheet93_cases.py" % (2 * d, d, dr))
    q.plane([d + dr, Y0, 0], [1, 0, 0], [0, 1, 0], [0, L - d - dr, 0, Y1 - Y0])          # +z
    q.cylinder([d + dr, 0, -dr], [0, 1, 0], [0, 0, 1], dr, [-90, 0, Y0, Y1])            # from +z to -x
    q.plane([d, Y0, -100], [0, 0, 1], [0, 1, 0], [0, 100 - dr, 0, Y1 - Y0])             # -x
    q.write(os.path.join(TOOLS, "numisheet93_uchannel_die.tool"))
    # blank holder: face z = t over the die's flat face, normal -z
    h = ToolFile("NUMISHEET'93 2D draw bending: blank holder (half), face z = t over the die's face\n"
                 "(x >= %g); written by scripts/make_numisheet93_cases.py" % (d + dr))
    h.plane([d + dr, Y0, t], [0, 1, 0], [1, 0, 0], [0, Y1 - Y0, 0, L - d - dr])          # -z
    h.write(os.path.join(TOOLS, "numisheet93_uchannel_holder.tool"))


def cup_tools(tag="cup"):
    C = CUPS[tag][0]
    t = C["t"]
    a, rc, rp = C["punch_half"], C["punch_corner"], C["punch_r"]
    d, dc, dr = C["die_half"], C["die_corner"], C["die_r"]
    c = a - rc                     # plan centre of the punch's corner (and of the die's: d - dc)
    assert abs(c - (d - dc)) < 1e-12
    S, F, H = -5.0, 130.0, 80.0    # start past the symmetry planes, far extent of the flat faces, wall height
    f = a - rp                     # half side of the punch's flat head
    rf = rc - rp                   # plan corner radius of the flat head
    # punch (quarter): flat head z = t, straight profile cylinders, corner blend, walls; normals outwards
    p = ToolFile("NUMISHEET'93 square cup: punch (quarter, x, y >= 0), %g x %g, plan corner radius %g,\n"
                 "profile radius %g, head on the sheet's top face z = t at load 0 (one square plane); the corner\n"
                 "blend is a spindle torus (major radius %g < minor %g) on its outer part;\n"
                 "written by scripts/make_numisheet93_cases.py" % (2 * a, 2 * a, rc, rp, rf, rp))
    # the flat head as one square plane up to the profile's start (x, y <= f): beyond the head's plan
    # corner radius rf it overreaches the corner blend by at most rp - sqrt(rp^2 - (sqrt(2) rf - rf)^2)
    # (0.04 mm at the square's corner), simpler than two strips and a quarter disc
    p.plane([S, S, t], [0, 1, 0], [1, 0, 0], [0, f - S, 0, f - S])                      # -z
    p.cylinder([f, 0, t + rp], [0, -1, 0], [0, 0, -1], rp, [0, 90, -c, -S])              # side x = a
    p.cylinder([0, f, t + rp], [1, 0, 0], [0, 0, -1], rp, [0, 90, S, c])                 # side y = a
    # the corner blend: the profile arc swept about the corner's axis, a torus of major radius rf <
    # minor rp (a spindle torus) on the tube angles -90..0, where the distance from the axis
    # rf + rp cos(ps) stays >= rf. (Until 2026-11-25 a Coons patch of its four boundary arcs, whose
    # interior lies up to 0.40 mm inside the torus near the diagonal: doc/notes/forming-log.md, Status.)
    p.torus([c, c, t + rp], [0, 0, 1], [1, 0, 0], rf, rp, [0, 90, -90, 0])
    p.plane([a, S, t + rp], [0, 1, 0], [0, 0, 1], [0, c - S, 0, H])                      # +x
    p.plane([S, a, t + rp], [0, 0, 1], [1, 0, 0], [0, H, 0, c - S])                      # +y
    p.cylinder([c, c, t + rp], [0, 0, 1], [1, 0, 0], rc, [0, 90, 0, H])                  # corner wall
    p.write(os.path.join(TOOLS, "numisheet93_%s_punch.tool" % tag))

    def flat(tool, z, sense):
        """the face z outside the rounded square of half side d + dr, corner radius dc + dr."""
        g, rg = d + dr, dc + dr
        tool.plane([g, S, z], [1, 0, 0], [0, 1, 0], [0, F - g, 0, c - S], sense)
        tool.plane([S, g, z], [1, 0, 0], [0, 1, 0], [0, c - S, 0, F - g], sense)
        R2 = F - c
        tool.coons([("arc", [c + rg, c, z], [c, c + rg, z], [c, c, z]),
                    ("arc", [c + R2, c, z], [c, c + R2, z], [c, c, z]),
                    ("line", [c + rg, c, z], [c + R2, c, z]),
                    ("line", [c, c + rg, z], [c, c + R2, z])], -sense)
    # die (quarter): face z = 0, shoulder (cylinders + torus), walls facing the cavity
    q = ToolFile("NUMISHEET'93 square cup: die (quarter), face z = 0, opening %g x %g, plan corner radius %g,\n"
                 "shoulder radius %g; written by scripts/make_numisheet93_cases.py" % (2 * d, 2 * d, dc, dr))
    flat(q, 0.0, 1)                                                                       # +z
    q.cylinder([d + dr, 0, -dr], [0, 1, 0], [0, 0, 1], dr, [-90, 0, S, c])               # side x = d: +z to -x
    q.cylinder([0, d + dr, -dr], [1, 0, 0], [0, 0, 1], dr, [0, 90, S, c])                # side y = d: +z to -y
    q.torus([c, c, -dr], [0, 0, 1], [1, 0, 0], dc + dr, dr, [0, 90, 90, 180])            # corner shoulder
    q.plane([d, S, -H], [0, 0, 1], [0, 1, 0], [0, H - dr, 0, c - S])                     # -x
    q.plane([S, d, -H], [1, 0, 0], [0, 0, 1], [0, c - S, 0, H - dr])                     # -y
    q.cylinder([c, c, -H], [0, 0, 1], [1, 0, 0], dc, [0, 90, 0, H - dr], -1)             # corner wall, concave
    q.write(os.path.join(TOOLS, "numisheet93_%s_die.tool" % tag))
    h = ToolFile("NUMISHEET'93 square cup: blank holder (quarter), face z = t over the die's face;\n"
                 "written by scripts/make_numisheet93_cases.py")
    flat(h, t, -1)                                                                        # -z
    h.write(os.path.join(TOOLS, "numisheet93_%s_holder.tool" % tag))


# ---------------------------------------------------------------- cases (.opts)
def material(m, eas=True):
    """Hill 1948, or Barlat 1991 where m names its exponent (key yld91), on the r-values"""
    yf = ["-material_type yld91", "-material_yld91_exponent %d" % m["yld91"]] if "yld91" in m else ["-material_type hill48"]
    p = "-material_yld91_" if "yld91" in m else "-material_hill_"
    return yf + ["-material_E %g" % m["E"], "-material_nu %g" % m["nu"],
                 "-material_hardening swift",
                 "-material_swift_K %g" % m["K"], "-material_swift_eps0 %g" % m["eps0"], "-material_swift_n %g" % m["n"],
                 p + "r0 %g" % m["r0"], p + "r45 %g" % m["r45"], p + "r90 %g" % m["r90"],
                 p + "rd 1,0,0", p + "normal 0,0,1",
                 "-element_type hex8_eas"]


def write_case(name, header, lines):
    with open(os.path.join(CASES, name + ".opts"), "w") as f:
        for h in header.splitlines():
            f.write("# %s\n" % h)
        f.write("\n".join(lines) + "\n")


def process_opts(mu, f_holder, holder_amplitude, stroke, stages, nsteps, bcs):
    """the options the process cases share: contact set and friction per tool, the holder driven by
    its force, the punch's stroke; then the stages: close (4 steps) and draw (nsteps), both with
    every tool and the conditions bcs, and the names of all stages."""
    return ["-tool_punch_contact_set top", "-tool_die_contact_set bottom", "-tool_holder_contact_set top",
            "-tool_punch_friction %g" % mu, "-tool_die_friction %g" % mu,
            "-tool_holder_friction %g" % mu,
            "-tool_holder_force_z %.10g" % -f_holder,
            "-tool_holder_force_amplitude %s" % holder_amplitude,
            "-tool_punch_motion 0,0,%g" % -stroke,
            "-tool_punch_amplitude 0,0,1,0,2,1",
            "-stage_names %s" % ",".join(stages),
            "-stage_close_duration 1", "-stage_close_steps 4",
            "-stage_close_tools punch,die,holder", "-stage_close_bcs %s" % bcs,
            "-stage_draw_duration 1", "-stage_draw_steps %d" % nsteps,
            "-stage_draw_tools punch,die,holder", "-stage_draw_bcs %s" % bcs]


def uchannel_cases(level, h, gap=True):
    mesh = "cases/sheets/numisheet93_uchannel_%s.inp" % level
    sym = 2 * U["width"] / h            # half model, strip h wide out of the blank's 35 mm
    f_holder = U["bhf"] / sym           # the holder's force on the modelled strip
    nsteps = {"coarse": 140, "fine": 280, "xfine": 560}[level]
    common = ["-mesh_type inp", "-mesh_file " + mesh] + material(MILD) + [
        "-model_symmetry %.10g" % sym,
        "-tool_names punch,die,holder",
        "-tool_punch_file cases/tools/numisheet93_uchannel_punch.tool",
        "-tool_die_file cases/tools/numisheet93_uchannel_die.tool",
        "-tool_holder_file cases/tools/numisheet93_uchannel_holder.tool",
    ]
    head = ("NUMISHEET'93 2D draw bending (U-channel), mild steel, blank holder force %g kN, %s mesh:\n"
            "half model (x >= 0) of a strip %g wide (one element, plane strain: y fixed on both sides),\n"
            "%d x 1 x 1 hexahedra (hex8_eas), t = %g; tools from cases/tools/numisheet93_uchannel_*.tool;\n"
            "data and sources: doc/forming.md. Written by scripts/make_numisheet93_cases.py."
            % (U["bhf"] / 1000, level, h, MESHES["uchannel"][level], U["t"]))
    write_case("numisheet93_uchannel_%s" % level,
               head + "\nProcess: close (the holder's force ramps to its value), draw (punch stroke %g),\n"
               "release (the tools removed, the contact force of each of their nodes falling to zero),\n"
               "springback (no tools; the centre line held where the draw left it)." % U["stroke"],
               common + [
                   "-bc_names symx,sides,pin",
                   "-bc_symx_components x", "-bc_sides_components y", "-bc_pin_components z",
                   # the centre line's bottom edge held where the draw left it (release and springback)
                   "-bc_pin_hold",
               ] + process_opts(U["mu"], f_holder, "0,0,1,1,2,1,2.5,0", U["stroke"],
                                ("close", "draw", "release", "springback"), nsteps, "symx,sides") + [
                   "-stage_release_duration 0.5", "-stage_release_steps 10",
                   "-stage_release_tools punch,die,holder", "-stage_release_release punch,die,holder",
                   # by nodal forces: released by force, the die and the punch follow the sheet as
                   # their forces fall (the die 42 mm down and 10 mm out, along x across the
                   # symmetry plane), and their contact bends the wall and the flange plastically
                   # in the release; the springback then depends on that path
                   # (doc/notes/forming-log.md, "The U-channel's release")
                   "-stage_release_release_mode nodes",
                   "-stage_release_bcs symx,sides,pin",
                   "-stage_springback_duration 0.5", "-stage_springback_steps 5",
                   "-stage_springback_tools none", "-stage_springback_bcs symx,sides,pin",
                   "-output_interval 10",
                   "-output_dir out/numisheet93_uchannel_%s" % level])
    if not gap:
        return
    write_case("numisheet93_uchannel_%s_gap" % level,
               head + "\nWith today's options: the holder fixed at a gap equal to the thickness (its face on the\n"
               "sheet's top face), one contact set and friction for all tools; the drawing only (no release).",
               common + contact(100) + [
                   "-bc_names symx,sides",
                   "-bc_symx_components x", "-bc_sides_components y",
                   "-contact_set top,bottom",
                   "-contact_friction %g" % U["mu"],
                   "-tool_punch_motion 0,0,%g" % -U["stroke"],
                   "-load_steps %d" % nsteps, "-load_dt_max %g" % (1.0 / nsteps),
                   "-output_interval 10",
                   "-output_dir out/numisheet93_uchannel_%s_gap" % level])


def cup_cases(level, tag="cup", gap=True):
    CUP, m, mname = CUPS[tag]
    n = MESHES["cup"][level]
    mesh = "cases/sheets/numisheet93_%s_%s.inp" % (tag, level)
    f_holder = CUP["bhf"] / 4
    nsteps = {"coarse": 80, "fine": 160}[level]
    common = ["-mesh_type inp", "-mesh_file " + mesh] + material(m) + [
        "-model_symmetry 4",
        "-tool_names punch,die,holder",
        "-tool_punch_file cases/tools/numisheet93_%s_punch.tool" % tag,
        "-tool_die_file cases/tools/numisheet93_%s_die.tool" % tag,
        "-tool_holder_file cases/tools/numisheet93_%s_holder.tool" % tag,
    ]
    head = ("NUMISHEET'93 square cup deep drawing, %s, blank holder force %g kN, %s mesh:\n"
            "quarter model (x, y >= 0; x the rolling direction), blank 150 x 150 x %g (quarter 75 x 75),\n"
            "%d x %d x 1 hexahedra (hex8_eas); punch stroke %g (draw-in read at 15 and 40);\n"
            "tools from cases/tools/numisheet93_%s_*.tool; data and sources: doc/forming.md.\n"
            "Written by scripts/make_numisheet93_cases.py."
            % (mname, CUP["bhf"] / 1000, level, CUP["t"], n, n, CUP["stroke"], tag))
    write_case("numisheet93_%s_%s" % (tag, level),
               head + "\nProcess: close (the holder's force ramps to its value), draw (punch stroke %g)."
               % CUP["stroke"],
               common + [
                   "-bc_names symx,symy",
                   "-bc_symx_components x", "-bc_symy_components y",
               ] + process_opts(CUP["mu"], f_holder, "0,0,1,1,2,1", CUP["stroke"], ("close", "draw"), nsteps,
                                "symx,symy") + [
                   "-output_interval 1",
                   "-output_dir out/numisheet93_%s_%s" % (tag, level)])
    if not gap:
        return
    write_case("numisheet93_cup_%s_gap" % level,
               head + "\nWith today's options: the holder fixed at a gap equal to the thickness, one contact set\n"
               "and friction for all tools, no stages.",
               common + contact(1000) + [
                   "-bc_names symx,symy",
                   "-bc_symx_components x", "-bc_symy_components y",
                   "-contact_set top,bottom",
                   "-contact_friction %g" % CUP["mu"],
                   "-tool_punch_motion 0,0,%g" % -CUP["stroke"],
                   "-load_steps %d" % nsteps, "-load_dt_max %g" % (1.0 / nsteps),
                   "-output_interval 1",
                   "-output_dir out/numisheet93_cup_%s_gap" % level])


def cup_gap110_case(level):
    """the fixed-gap cup with the holder lifted to a gap of 1.1 t between 10 and 15 % of the stroke: the
    flange thickens under the hoop compression and a gap of t locks it. (Lifted from the start, the
    flange is free to tilt about the die's shoulder and the first step does not converge.)"""
    src = os.path.join(CASES, "numisheet93_cup_%s_gap.opts" % level)
    lines = open(src).read().splitlines()
    head = [l for l in lines if l.startswith("#")]
    body = [l for l in lines if not l.startswith("#") and not l.startswith("-output_dir")]
    lift = 0.1 * CUP["t"]
    head.append("# Variant: the holder lifted by %g (a gap of 1.1 t) between 10 and 15 %% of the stroke, then held." % lift)
    body += ["-tool_holder_path 0,0,0,0,0.1,0,0,0,0.15,0,0,%g,1,0,0,%g" % (lift, lift),
             "-output_dir out/numisheet93_cup_%s_gap110" % level]
    with open(os.path.join(CASES, "numisheet93_cup_%s_gap110.opts" % level), "w") as f:
        f.write("\n".join(head + body) + "\n")


def main():
    os.makedirs(SHEETS, exist_ok=True)
    uchannel_tools()
    for tag in CUPS:
        cup_tools(tag)
    for level in ("coarse", "fine"):
        _, h = uchannel_mesh(level)
        uchannel_cases(level, h)
        cup_mesh(level)
        cup_cases(level)
        cup_gap110_case(level)
        cup_mesh(level, "cup_al")
        cup_cases(level, "cup_al", gap=False)    # the process only
    _, h = uchannel_mesh("xfine")                 # the U-channel's mesh convergence: 0.25 mm
    uchannel_cases("xfine", h, gap=False)


if __name__ == "__main__":
    main()
