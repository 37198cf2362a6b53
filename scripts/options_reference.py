#!/usr/bin/env python3
"""The options reference, generated from what the code registers: doc/reference/options.md.

Runs `bin/atrito -help` on a set of probes that together select every registered type (mesh
sources, materials, elements, tool patch types, force-driven tools, stages, the preconditioner
amgsys), parses the groups the code's modules print (PETSc's own groups are left to PETSc's
manual pages), names the per-object options generically (-tool_<t>_..., -bc_<b>_...,
-stage_<s>_..., -tool_<t>_patch<j>_...) and writes one list per group: option, default, the text
-help prints. The registered types are listed from the "(one of)" choices of the type options.

  scripts/options_reference.py            write doc/reference/options.md
  scripts/options_reference.py --check [--file F]
                                          compare with it (or with F); exit 1 on a difference
                                          or on an option without a description
                                          (tests/test_options.sh)
"""
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "doc", "reference", "options.md")
BIN = os.path.join(ROOT, "bin", "atrito")

# the probes: a small box with one condition, one stage and one tool whose patches are given as
# options (a .tool file's lines, prefixed), and the tutorial's process for the stages' releases,
# the force-driven tools, Hill's material, the EAS element and amgsys
T, B, S = "tq", "bq", "sq"
BASE = ["-mesh_type", "box", "-box_cells", "2,2,1",
        "-bc_names", B, f"-bc_{B}_set", "zmin", f"-bc_{B}_components", "x,y,z",
        "-contact_set", "zmax",
        "-stage_names", S, f"-stage_{S}_tools", T, "-tool_names", T]


def tool_options(path):
    """a .tool file's lines (the patch options without -tool_<t>_) as this tool's options"""
    out = []
    for line in open(os.path.join(ROOT, path)):
        line = line.split("#", 1)[0].split()
        if len(line) >= 2:
            out += [f"-tool_{T}_{line[0]}", line[1]]
    return out


PROBES = [BASE + tool_options("tests/data/tool_patches.tool"),                       # plane, sphere
          BASE + tool_options("cases/tools/cylcup_die.tool"),                         # coons (lines, arcs), torus, cylinder
          BASE + [f"-tool_{T}_patches", "1", f"-tool_{T}_patch0_type", "facets",
                  f"-tool_{T}_patch0_file", "tests/data/tool_square_bin.stl"],        # facets
          BASE + [f"-tool_{T}_file", "tests/data/tool_patches.tool", "-material_type", "yld91"],
          BASE + [f"-tool_{T}_file", "tests/data/tool_patches.tool", "-material_type", "umat"],
          ["-options_file", "cases/cylindrical_cup.opts", "-options_file", "cases/solver_process.opts"],
          ["-options_file", "cases/pair_patch.opts",                                  # contact pairs, bodies
           "-body_names", "bq", "-body_bq_set", "UPPER"]]

OURS_SKIP = re.compile(r"^(Options for all PETSc programs|PetscDevice|Root PetscDeviceContext|Viewer \(|Nonlinear solver \(SNES\)|"
                       r"Eisenstat and Walker|Linesearch \(SNESLineSearch\)|Krylov Method \(KSP\)|Vector \(Vec\)|Matrix \(Mat\)|"
                       r"Preconditioner \(PC\)|DM |DMPlex|PetscSection|Partitioner|SNES|KSP|PC )")
OPT = re.compile(r"^  (-[A-Za-z0-9_<>]+):?\s*(?:<([^>]*)>)?:?\s*(.*)$")


def names_of(text):
    """the object names of a -help output and how the reference writes them"""
    pairs = []
    for kind, title, opt, gen in (("tool", "Tool", "-tool_", "<t>"), ("bc", "Boundary condition", "-bc_", "<b>"),
                                  ("stage", "Stage", "-stage_", "<s>"), ("pair", "Pair", "-pair_", "<p>"),
                                  ("body", "Body", "-body_", "<body>")):
        for n in sorted(set(re.findall(rf"^{title} ([A-Za-z0-9]+)(?: contact)?:$", text, re.M)), key=len, reverse=True):
            pairs.append((f"{opt}{n}_", f"{opt}{gen}_"))
            pairs.append((f"{title} {n}", f"{title} {gen}"))
    return pairs


def norm(s, pairs):
    for a, b in pairs:
        s = s.replace(a, b)
    return re.sub(r"_patch[0-9]+_", "_patch<j>_", s)


def given_options(probe):
    """the options a probe gives: on its command line and in its options files"""
    out, args = set(), list(probe)
    for k, a in enumerate(args):
        if a == "-options_file":
            for line in open(os.path.join(ROOT, args[k + 1])):
                if line.startswith("-"):
                    out.add(line.split()[0])
        elif a.startswith("-"):
            out.add(a)
    return out


def default_of(raw):
    """The default -help prints: 'now X : formerly Y' or 'X : Y' -> Y (the value before the
    options were read); a single value is the one the probe set or the default"""
    if raw is None:
        return ""
    m = re.match(r"^now (.*) : formerly (.*)$", raw)
    if m:
        return m.group(2).strip()
    if " : " in raw:
        return raw.split(" : ", 1)[1].strip()
    return raw.strip()


def parse(text, probe):
    """groups of the code's modules: [(title, [(subheading, option, default, description)])]; the
    subheading names the patch type whose parameters follow its -tool_<t>_patch<j>_type"""
    pairs = names_of(text)
    given = {norm(a, pairs) for a in given_options(probe)}
    groups, target, sub = [], None, None
    for line in text.splitlines():
        if line.startswith("---"):
            target = None
            continue
        if line and not line.startswith(" ") and line.rstrip().endswith(":"):
            title = line.rstrip()[:-1]
            target = None if OURS_SKIP.match(title) else (norm(title, pairs), [])
            if target:
                groups.append(target)
            sub = None
            continue
        if line.startswith("  BoomerAMG for the displacements"):  # amgsys: its options inside PETSc's PC group
            target = ("Preconditioner amgsys: " + line.strip(), [])
            groups.append(target)
            sub = None
            continue
        m = OPT.match(line)
        if target is None or not m:
            continue
        name, raw, desc = m.group(1), m.group(2), m.group(3)
        name = norm(name, pairs)
        if target[0].startswith("Preconditioner amgsys") and not name.startswith("-pc_amgsys"):
            continue
        desc = re.sub(r"\s*\((None|\(null\)|[A-Za-z0-9_/.-]+(\.md|\.h)|[A-Z][A-Za-z]+)\)\s*$", "", desc.strip())
        d = default_of(raw)
        if d == "string1,string2,...":  # PETSc's placeholder of a string array
            d = ""
        if name in given:
            m2 = re.match(r"^now (.*) : formerly (.*)$", raw or "")
            if not (m2 and m2.group(1).strip() != m2.group(2).strip()):
                d = "–"  # -help prints the probe's value; the default is not known from it
        if name.endswith("_patch<j>_type"):
            sub = (re.match(r"^now (\S+)", raw or "") or re.match(r"(\S+)", raw or "x")).group(1).capitalize() + " patch"
            target[1].append((None, name, "–", norm(desc, pairs)))
            continue
        in_patch = "_patch<j>_" in name and not name.endswith("_patch<j>_sense")
        target[1].append((sub if in_patch else None, name, norm(d, pairs), norm(desc, pairs)))
    return groups


PC_OWN = ["amgsys"]  # the preconditioners the code registers (src/solver/amg.c), checked against -help


def collect():
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    merged, order, pcs = {}, [], set()
    with tempfile.TemporaryDirectory() as tmp:
        for probe in PROBES:
            r = subprocess.run([BIN, "-help"] + probe, cwd=ROOT, env=env,
                               capture_output=True, text=True, timeout=120)
            if r.returncode != 0 or "atrito: error" in r.stdout + r.stderr:
                err = [l for l in (r.stdout + r.stderr).splitlines() if "atrito: error" in l][:1]
                sys.exit(f"options_reference: -help failed on the probe {' '.join(probe)}: {err}")
            m = re.search(r"^  -pc_type <[^>]*>: Preconditioner \(one of\) (.*) \(PCSetType\)$", r.stdout, re.M)
            if m:
                pcs |= set(m.group(1).split())
            for title, opts in parse(r.stdout, probe):
                if title not in merged:
                    merged[title] = []
                    # a type's group after the last group of its kind ("Material hill48" after "Material ...")
                    kind = re.split(r"[ :]", title)[0]
                    at = max([k + 1 for k, t in enumerate(order) if re.split(r"[ :]", t)[0] == kind], default=len(order))
                    order.insert(at, title)
                have = {(o[0], o[1]) for o in merged[title]}
                for o in opts:
                    if (o[0], o[1]) not in have:
                        merged[title].append(o)
                        have.add((o[0], o[1]))
    missing = [p for p in PC_OWN if p not in pcs]
    if missing:
        sys.exit(f"options_reference: -pc_type does not list {' '.join(missing)} on any probe")
    return [(t, merged[t]) for t in order]


def render(groups):
    out = ["# Options reference",
           "",
           "Generated by `scripts/options_reference.py` from what `bin/atrito -help` prints: every option the",
           "code's modules register, grouped as `-help` groups them, with the default `-help` shows (\"–\": none",
           "known, the option is given). `<t>`, `<b>`, `<s>`, `<p>`, `<body>` stand for a tool's, a boundary",
           "condition's, a stage's, a contact pair's and a body's name, `<j>` for a patch's number. Do not edit: `tests/test_options.sh` fails when this page",
           "differs from the code. What the options do and how to choose them: [options.md](../options.md).",
           ""]
    choices, seen = [], set()
    for title, opts in groups:
        for sub, name, d, desc in opts:
            m = re.search(r"\((?:choose )?one of\)\s*(.*)$", desc)
            if m and name not in seen:
                seen.add(name)
                choices.append((name, m.group(1).split()))
    out += ["## Registered types and choices", "", "| option | values |", "|---|---|",
            f"| `-pc_type` (the code's own) | {', '.join(PC_OWN)} |"]
    for name, ts in choices:
        out.append(f"| `{name}` | {', '.join(ts)} |")
    out.append("")
    for title, opts in groups:
        out += [f"## {title}", ""]
        subs = [None] + sorted({o[0] for o in opts if o[0]}, key=lambda x: [o[0] for o in opts].index(x))
        for sub in subs:
            if sub:
                out += ["", f"{sub}:", ""]
            for s_, name, d, desc in opts:
                if s_ != sub:
                    continue
                dd = "no default" if d == "–" else f"default `{d}`" if d else "default empty"
                out.append(f"- `{name}` ({dd}): {desc}")
        out.append("")
    return "\n".join(out).rstrip() + "\n"


def undocumented(groups):
    return [name for _, opts in groups for sub, name, d, desc in opts if len(desc.strip()) < 3]


def main():
    groups = collect()
    text = render(groups)
    bad = undocumented(groups)
    if "--check" in sys.argv:
        path = sys.argv[sys.argv.index("--file") + 1] if "--file" in sys.argv else OUT
        old = open(path).read() if os.path.exists(path) else ""
        ok = True
        if bad:
            print("options without a description: " + " ".join(bad))
            ok = False
        if old != text:
            a, b = old.splitlines(), text.splitlines()
            diff = [f"- {x}" for x in a if x not in b][:5] + [f"+ {x}" for x in b if x not in a][:5]
            print(f"{path} differs from the code's options (run scripts/options_reference.py):")
            print("\n".join(diff))
            ok = False
        n = sum(len(o) for _, o in groups)
        print(f"{n} options in {len(groups)} groups" + ("" if ok else ": not ok"))
        sys.exit(0 if ok else 1)
    if bad:
        sys.exit("options_reference: options without a description: " + " ".join(bad))
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as f:
        f.write(text)
    print(f"wrote {os.path.relpath(OUT, ROOT)}: {sum(len(o) for _, o in groups)} options in {len(groups)} groups")


if __name__ == "__main__":
    main()
