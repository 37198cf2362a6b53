#!/usr/bin/python3
"""One million hexahedra: memory, Krylov iterations and time per Newton iteration of large sheets.

  /usr/bin/python3 scripts/bench_million.py [--point NC,NR,STEPS,TRAVEL,RANKS[,m] ...] [--timeout S]
                                            [--logdir DIR] [--reuse]
                                            [--output doc/notes/performance-log.md]
                                            [--solver cases/solver_amgsys_sheet.opts]

What it does
  1. Runs the friction benchmark on the whole 4-layer blank (cases/hemisphere_friction_disk.opts:
     analytic tools, contact penalties per unit area; -blank_core_cells NC -blank_radial_cells NR,
     4 (NC^2 + 2 NC NR) quadrilaterals per layer) with the iterative solver of
     cases/solver_amg_sheet.opts, no field output, -memory_view -memory_phases -log_view, for each
     --point: punch travel TRAVEL mm in STEPS equal steps (the first contact and the onset of
     plasticity are in the first millimetre) on RANKS ranks. Default points: 25 600 hexahedra on
     1 rank, one step of 1 mm; 100 352, 250 512 and 1 010 224 on 2 ranks, memory only (below), and
     250 512 on 2 ranks, one step of 1 mm.
  2. Reads from each log: the peak resident set size (PETSc's "Maximum (over computational time)
     process memory", summed over the ranks), the memory after the setup phases, the Newton and
     Krylov iterations of every step (the progress line's "krylov N (most M)"), the solve time, and
     from -log_view the time in assembly (SNESFunctionEval + SNESJacobianEval), preconditioner
     setup (PCSetUp) and Krylov iterations (KSPSolve less PCSetUp).
  3. Writes the section "## One million hexahedra" of the output file, keeping its other sections
     and the section's own '### ' subsections that it does not write itself (the analyses and
     later measurements added by hand: the iteration bound, the sheet's coarse space).

A point ending in ",m" is a memory-only run: no tangent predictor (-load_predictor none), one
Newton iteration (-snes_max_it 1, -load_max_cuts 0: the Jacobian, BoomerAMG's setup and one linear
solve, where the peak is reached), after which the step fails and the run ends; its row says so.

--logdir keeps the logs (default: a temporary directory, removed); --reuse reads the logs already
in --logdir instead of running (to rewrite the section from runs made earlier). A run past
--timeout (default 3000 s) is reported with the steps it completed and no log_view split.
Standard library only; OPENBLAS_NUM_THREADS=1 and the Open MPI run-as-root variables set.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

import benchutil

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE = "cases/hemisphere_friction_disk.opts"
SOLVER = "cases/solver_amg_sheet.opts"
HEADING = "## One million hexahedra"
LAYERS = 4
# (core cells, radial cells, steps, travel mm, ranks): hexahedra = 4 (nc^2 + 2 nc nr) per layer, 4 layers
POINTS = [(16, 42, 1, 1.0, 1, ""), (32, 82, 1, 1.0, 2, "m"), (51, 128, 1, 1.0, 2, "m"), (51, 128, 1, 1.0, 2, ""), (103, 255, 1, 1.0, 2, "m")]
MEMORY_ONLY = ["-load_predictor", "none", "-snes_max_it", "1", "-load_max_cuts", "0"]
TARGET_GIB = 0.8   # peak resident size per 100 000 hexahedra
TARGET_KRYLOV = 50  # Krylov iterations per Newton iteration

MEM_RE = benchutil.MEM_RE
MESH_RE = benchutil.MESH_RE
DONE_RE = benchutil.DONE_RE
STEP_RE = re.compile(r"^step\s+(\d+)\s+time\s+([\d.]+)\s+its\s+(\d+)\s+krylov\s+(\d+)\s+\(most\s+(\d+)\)\s+\|R\|\s+(\S+)\s+elapsed\s+([\d.]+) s", re.M)
CUT_RE = re.compile(r"^step \d+ at load .*retrying.*$", re.M)
PHASE_RE = re.compile(r"^memory: after (.*?): PetscMalloc\(\)ed [\d.]+ MiB, resident ([\d.]+) MiB(?:; Jacobian (\d+) nonzeros)?", re.M)
LSOLVE_RE = re.compile(r"Linear solve (converged|did not converge) due to \S+ iterations (\d+)")
SNESMON_RE = re.compile(r"^\s*(\d+) SNES Function norm")
FORCE_RE = re.compile(r"^(\w+)\s+(\d+)\s+[\d.]+\s+([\d.eE+-]+)\s+[\d.]+\s+([\d.eE+-]+)\s+[\d.]+", re.M)

# Measured by hand on 2026-11-24 (commit 7de706a and the next; 1 rank unless said; -memory_phases,
# -log_view_memory, -memory_view); kept with the section because the runs take hours to repeat.
NOTES = """The memory-only runs stop after the first Newton iteration of the first step (no tangent
predictor: the Jacobian, BoomerAMG's setup and one linear solve); the resident size reaches its
peak in that solve and stays there to its end (sampled every 0.5 s at 100 352 hexahedra with
P_max 2 and no aggressive coarsening: 721 MiB after the setup, 854 during BoomerAMG's setup, 901
from the first Krylov iteration on). A whole step (the tangent predictor's solve and the later
Newton iterations, BoomerAMG set up anew in each) went 5 % above its first Newton iteration at
25 600 hexahedra on 2 ranks (323 against 308 MB, the options before the aggressive coarsening),
0.7 % at 250 512 hexahedra with the options file (2.046 against 2.031 GB: 0.76 GiB per 100 000
hexahedra either way; 5 Newton iterations, at most 56 Krylov iterations in one); no whole step was
run at 1 010 224 hexahedra. The 25 600-hexahedra row is one rank: its
peak is the Jacobian's creation and the 45 MiB of libraries (below). The machine was shared
during every run (load 5 to 9 on its 2 cores): the times are wall times of a fraction of a core.

### What was cut

Peak resident size summed over the ranks (MiB), memory-only runs on 2 ranks; Krylov iterations
from whole steps of 1 mm on 1 rank at 25 600 hexahedra (total over the step, most in one Newton
iteration, Newton iterations, step time in s); each row adds its change to the rows above unless
it says "instead":

| change | 25 600 hex | 100 352 hex | 250 512 hex | Krylov at 25 600: total (most), Newton its, s | BoomerAMG operator complexity (25 600 / 100 352) |
|---|---|---|---|---|---|
| before: DMCreateMatrix in hypre's format, rigid-body modes, HMIS, P_max 4 | 362 (whole step) | – | – | 194 (46), 5, 61 | 1.54 / – |
| the Jacobian made with MAT_SORTED_FULL (below) | 294 (308 whole step) | – | – | 194 (46), 5, 59 (same iterations and residuals) | 1.54 / – |
| no rigid-body modes (`-assembly_near_null_space 0`) | 285 | 958 (0.93 GiB per 100 000) | – | 194 (46), 5, 62 (same) | 1.54 / – |
| BoomerAMG P_max 2 | 283 | 905 (0.88) | 2229 (0.87) | 208 (48), 5, 80 | – / 1.72 |
| P_max 2 and truncation factor 0.1 / PMIS coarsening / strength 0.5 | – | 905 / 912 / 903 | – | strength 0.5: 160 (44), 4, 62; strength 0.6: 218 (53) | 1.50 / 1.66 (strength 0.5) |
| instead: aggressive coarsening on the first level (`agg_nl 1`, P_max 4) | – | 829 (0.81) | – | 237 (59), 5, 69 | – |
| same with 2 paths / strength 0.5 | – | – | – | 196 (51) / 226 (62) | 1.54 / 1.20 |
| **aggressive first level and 2 smoothing sweeps (`cases/solver_amg_sheet.opts`)** | 279 | 829 (0.81) | 1937 (0.76) | **171 (40), 5, 58** | 1.18 / 1.15 |

The second sweep costs one more smoothing per level and V-cycle and saves more iterations than it
costs: 171 against 194 BiCGStab iterations in the step at 25 600 hexahedra, 58 s against 62. At
100 352 hexahedra (1 rank, whole step): 244 Krylov iterations, most 68 in a Newton iteration (70
before), 5 Newton iterations, 423 s for the step on the shared machine.

### Where the memory goes

100 352 hexahedra, 2 ranks, the options file, a memory-only run; resident size summed over the
ranks (`-memory_phases`) and what the parts must take by their sizes:

| phase | resident MiB | growth MiB | what grew |
|---|---|---|---|
| after the mesh and conditions | 193 | 193 | libraries and MPI (45 MiB per process on 1 rank), the DMPlex of cells and vertices (not interpolated, distributed), section, coordinates, cell dof maps: about 1 kB per hexahedron |
| after the contact setup | 208 | 16 | slave nodes, seeds, tributary areas, tool masks (0.16 kB per hexahedron) |
| after the problem setup | 724 | 516 | material history, committed and trial (8 points x 7 values x 2) and per-cell results (144 bytes): 100; the Jacobian in hypre's format, 26.2 million nonzeros x 12 bytes: 300; vectors, and memory freed by the matrix's creation that glibc keeps: 116 |
| peak, in the first linear solve | 829 | 105 | BoomerAMG's hierarchy (operator complexity 1.15), its level vectors and BiCGStab's, partly in the memory freed before |

The per-hexahedron part is what grows: from 100 352 to 250 512 hexahedra the peak grows by 7.4
MiB per 1 000 hexahedra (0.72 GiB per 100 000), and the 1 010 224-hexahedra run above lies on
that line.

The Jacobian in hypre's format (`src/solver/problem.c`, CreateHypreJacobian). PETSc 3.18's MATHYPRE
keeps beside hypre's matrix an auxiliary assembly structure: per row, arrays of column indices and
values that MatSetValues fills and the assembly copies into the matrix. DMCreateMatrix fills the
pattern with zeros through it (so for a moment the rows exist twice, with the DM's adjacency
beside them), and MatAssemblyEnd_HYPRE makes it anew after every assembly for the next
MatSetValues, although hypre adds into an assembled matrix directly (each (row, column) looked up
in its row; rows of other ranks in hypre's own off-processor buffers, freed at the assembly). The
code now creates the matrix itself, sets MAT_SORTED_FULL before the preallocation and lets
DMPlexPreallocateOperator preallocate and fill it: on more than one rank hypre then takes exact
row sizes and writes the zeros straight into its matrix, and on any number of ranks nothing is
made again after an assembly. The later assemblies are unchanged (same iterations and residuals
on 1 rank; on 2 ranks the order of the entries within a row differs, which moved the 25 600
hexahedra step from 205 to 200 Krylov iterations). On 1 rank PETSc preallocates hypre by row sizes
only and the first fill still goes through the auxiliary rows: there the matrix's creation (about
185 MiB at 25 600 hexahedra for a matrix of 76) is the peak of a one-step run.

The rigid-body modes are set on the Jacobian for GAMG; PCHYPRE copies them into hypre vectors and
hands them to BoomerAMG, which uses them only for the interpolation variants
(`-pc_hypre_boomeramg_vec_interp_variant`): 12 vectors, 0.36 kB per hexahedron, for nothing here.
`-assembly_near_null_space 0` leaves them out (default: set, the small cases do not move).

Not cut:
- the coordinate (COO) assembly, the default, keeps per hexahedron 576 values (4.6 kB) in the code
  and PETSc's permutation and map (4.6 + 2.4 kB): about 12 kB per hexahedron. The large runs use
  MatSetValues (`-assembly_coo 0` in the options file); the default stays, the small cases'
  results do not move.
- the trial history (0.45 kB per hexahedron) and the per-cell results (0.14 kB): kept; the trial
  state could be recomputed at the commit instead of stored.
- glibc keeps freed memory of the setup (the matrix's creation, the mesh distribution):
  `malloc_trim(0)` after the setup lowered the resident size after it (724 to 615 MiB at 100 352
  hexahedra) but not the peak (1002.6 against 1004.1 MB): BoomerAMG's setup reuses that memory.
- GAMG on the quarter blank: the symmetry planes remove single components, the matrix has no 3 x 3
  blocks, and PETSc 3.18's GAMG builds its graph from the whole scalar matrix: a copy, its
  transpose and their sum (MatConvert 81, MatTranspose 79, MatAXPY 81 MiB at 25 476 hexahedra).
  The large runs use the whole blank (`cases/hemisphere_friction_disk.opts`).

The run before these changes (commit 3b4e773, 01:48 UTC, 1 010 224 hexahedra, 2 ranks, P_max 4
without aggressive coarsening): peak 13.02 GiB (1.29 GiB per 100 000 hexahedra), 9.58 GiB after
the setup; stopped after 41 minutes inside its first step (Newton residual 1359, 312, 112 after two
iterations; 32 and 61 Krylov iterations, 426 and 744 s).

### The iteration bound: what was tried

Krylov iterations in one Newton iteration, most over the first load step (1 mm: first contact,
plasticity starting), whole blank of 9 600 hexahedra unless said:

| preconditioner, Krylov method, relative tolerance | most | Newton its | step s |
|---|---|---|---|
| GAMG default (Chebyshev/Jacobi), GMRES, 1e-8 (25 600 hexahedra) | 793 | 4 | 85 |
| GAMG, SOR x4 smoother, GMRES, 1e-4 (two steps of 0.5 mm) | 307 | 4, 6 | 48, 31 |
| same, graph threshold 0.02 / 0.08 | 238 / 205 | 4 | 26 / 21 |
| same, threshold 0.08, SOR x8 | 189 | 4 | 59 |
| same, threshold 0.08, no aggressive coarsening (SOR or Chebyshev/SOR) | linear solve diverged | – | – |
| BoomerAMG (strength 0.7), GMRES, 1e-4 | 75 | 4 | 7 |
| + nodal coarsening (6) / + GM-2 interpolation of the rigid-body modes | 82 / 62 | 4 | 6 / 21 (twice the memory) |
| BoomerAMG HMIS, ext+i, P_max 4 (the file's), GMRES(30), 1e-4 / 1e-3 | 73 / 69 | 4 / 5 | 6 / 6 |
| same, 1e-3, GMRES(100) / CG | 55 / 56 | 5 | 4 / 6 |
| same, 1e-3, BiCGStab (`cases/solver_amg_sheet.opts` before the aggressive coarsening) | 38 | 5 | 8 |
| **same, aggressive coarsening on the first level, 2 sweeps** (`cases/solver_amg_sheet.opts`) | **35** | 5 | 24 (shared machine) |

GAMG does not come near the bound on these thin 4-layer sheets (0.25 mm layers, 1.7 mm cells in
the plane) with contact; BoomerAMG with BiCGStab holds it. One BiCGStab iteration applies the
matrix and the preconditioner twice: 38 BiCGStab iterations cost about as much as 76 of GMRES.

To 40 mm (`cases/hemisphere_friction_disk.opts`, 9 600 hexahedra, 1 rank), the options file of now:
27 steps, 192 Newton iterations, no cut, 675 s on the shared machine; the most Krylov iterations in
a Newton iteration, steps 1 to 27: 35, 30, 27, 20, 23, 22, 18, 23, 35, 42, 37, 44, 39, 46, 38, 34,
31, 26, 29, 30, 32, 29, 33, 36, 34, 37, 53 (the last step, 10 Newton iterations, is the one above
50); punch force at 40 mm 79.372 kN, as before. With the options before the aggressive coarsening
(`-pc_hypre_boomeramg_agg_nl 0 -pc_hypre_boomeramg_grid_sweeps_all 1`): 27 steps, 189 Newton
iterations, no cut, at most 47 Krylov iterations in a Newton iteration (steps 1 to 27: 38, 31, 22,
22, 21, 18, 20, 24, 21, 32, 32, 32, 38, 35, 42, 27, 30, 22, 27, 27, 25, 33, 26, 28, 29, 32, 47),
against LU (MUMPS): 27 steps, 203 Newton iterations, 1 cut (at 35 mm). The punch force at 40 mm:
79.372 kN against 79.371 kN with LU (+0.001 %). The two runs take the same steps to 19 mm and
their forces agree there to 8 digits; from there the step sequences differ (the step growth follows
the Newton iterations, 6 against 5 at 19 mm) and the punch forces at the common points differ by at
most 0.04 %.

Growth with the mesh (the whole blank, one step of 1 mm, the options file before
`-assembly_mat_type hypre`, i.e. with hypre's copy of an AIJ matrix): 9 600 hexahedra at most 38
Krylov iterations per Newton iteration, 25 600: 49, 100 352 (1 rank): 70, with 4 Newton iterations,
peak 1.405 GB (1.30 GiB per 100 000 hexahedra), 62.6 s per Newton iteration on a machine whose other
processes took about half of it (assembly 1.4, BoomerAMG setup 1.4, Krylov 57.9 s; a V-cycle
0.47 s). The bound of 50 is held to about 25 000 hexahedra; BoomerAMG's iterations grow with the
mesh here. 250 512 hexahedra on 2 ranks (with `-assembly_mat_type hypre`): 2.44 GiB resident after
the setup (0.97 GiB per 100 000 hexahedra before the first solve); stopped after 14 minutes before
its first step ended (the ranks had had 5 minutes of CPU each). With the options file of now
(aggressive coarsening on the first level, 2 sweeps, the Jacobian in hypre's format): 25 600
hexahedra at most 40 Krylov iterations per Newton iteration (5 Newton iterations, 171 in the step),
100 352 (1 rank) at most 68 (5 Newton iterations, 244 in the step, 423 s on the shared machine):
the bound is still held to 25 600 hexahedra, not above.

Quarter blanks (symmetry planes) with PCHYPRE: not held. `cases/hemisphere_friction_fine.opts`
(9 600 hexahedra) with `cases/solver_amg_sheet.opts` takes up to 143 and 136 Krylov iterations per
Newton iteration in its first two steps (with the options before the aggressive coarsening 178;
GAMG default: 382), `cases/hemisphere_friction_refined.opts` (3 612 hexahedra, 3 layers) 141 and
154 in two steps of 2 mm with the earlier options. The cause: a symmetry plane removes one unknown
of each of its nodes, the rows no longer come in threes, the matrix's block size is 1, and PCHYPRE
then hands BoomerAMG a scalar problem, whose coarsening and interpolation mix the x, y and z
components (the whole blank, clamped in all three components, keeps the block size 3).

**`-pc_type amgsys`** (`src/solver/amg.c`, `cases/solver_amgsys.opts`): BoomerAMG called
directly, each row told its component from the mesh's sections (`HYPRE_BoomerAMGSetDofFunc`, 3
functions), the rest as the sheet file (HMIS, aggressive first level, ext+i, P_max 4, strength
0.7, BiCGStab to 1e-3). The same quarter blank of 9 600 hexahedra, one rank, 2026-11-24 (machine
shared with one other run: times indicative), the most Krylov iterations in a Newton iteration of
the first two steps, their Krylov iterations and time:

| preconditioner | step 1 | step 2 | Krylov its | s |
|---|---|---|---|---|
| PCHYPRE (`solver_amg_sheet.opts`) | 143 | 136 | 528 + 569 | 54.0 |
| amgsys, 2 sweeps | 38 | 52 | 159 + 173 | 18.4 |
| amgsys, 3 sweeps (`solver_amgsys.opts`) | 35 | 35 | 151 + 147 | 25.6 |
| amgsys, 2 sweeps, no aggressive coarsening | 36 | 37 | 157 + 142 | 21.5 |
| amgsys, 2 sweeps, strength 0.5 | 51 | 43 | 200 + 158 | 21.4 |
| amgsys, 2 sweeps, l1 Gauss-Seidel (relax 8) | 55 | 39 | 191 + 165 | 21.3 |
| amgsys, 2 sweeps, GMRES(100) instead of BiCGStab | 61 | 54 | 240 + 214 | 14.7 |
| amgsys with hypre's nodal coarsening | crashed in hypre (it needs all three unknowns at every node): not offered | | | |

To 40 mm with `cases/solver_amgsys.opts`: 32 steps, 210 Newton iterations, 2 cuts, at most 35
Krylov iterations in any Newton iteration (per step: 35, 35, 24, 22, 19, 18, 23, 20, 24, 22, 26,
26, 24, 28, 25, 27, 27, 33, 24, 26, 25, 22, 20, 20, 20, 20, 20, 22, 21, 23, 21, 17), 415 s; LU
(MUMPS) on the same case: 32 steps, 201 Newton iterations, 2 cuts (the same two), 137 s. Punch
force at 40 mm 79.18767 kN both, within 3e-10 (at 10, 20, 30 mm within 2.5e-9). On the whole
blank (block size 3) amgsys and PCHYPRE do the same (9 600 hexahedra, first two steps: 35 and 36
against 35 and 30). `tests/test_solver.sh` runs a small quarter blank at 1 and 2 ranks against LU
and checks the bound and that amgsys needs fewer iterations than PCHYPRE.

On the whole blank, amgsys with `cases/solver_amgsys.opts` also needs fewer iterations than
PCHYPRE as the mesh grows, although PCHYPRE has the block size 3 there, in one step of 1 mm
(peak resident size of the whole step, summed over the ranks; the machine shared with one other
run). What differs is the order of the smoothing: PCHYPRE relaxes in CF order by default (the
coarse points first on the way down, the fine points first on the way up), amgsys in hypre's
natural order; with `-pc_hypre_boomeramg_grid_sweeps_all 3 -pc_hypre_boomeramg_no_CF` PCHYPRE
takes amgsys's Krylov iterations one for one (25 600 hexahedra, 1 rank: 25, 19, 30, 32, 35, 64
both, the same Newton residuals and peak memory). `-pc_amgsys_relax_order CF` offers PCHYPRE's
order.

| hexahedra, ranks | PCHYPRE, 2 sweeps (`solver_amg_sheet.opts`) | PCHYPRE, 3 sweeps | amgsys, 3 sweeps (`solver_amgsys.opts`) | amgsys, 4 sweeps |
|---|---|---|---|---|
| 100 352, 1 | most 68, 244 in the step, 423 s | most 89, 203, 283 s, 1.032e9 B | **most 49**, 200, 236 s, 1.032e9 B (0.96 GiB per 100 000 on one rank) | – |
| 250 512, 2 | most 56, 5 Newton its at 169 s each | – | most 54, 183 in the step, 5 Newton its, 304 s (61 s per Newton iteration), 2.065e9 B (0.77 GiB per 100 000) | most 58, 229, 6 Newton its, 463 s |
| 1 010 224, 2 | – (memory-only run: 23 in its first Newton iteration) | – | most 78: 59 in the predictor's solve, then 31, 51, 49, 45, 46, 37, 44, 78, 66 in the 9 Newton iterations; 2 888 s for the step (about 290 s per Newton iteration); peak 8.188e9 B (**0.755 GiB per 100 000**) | – |

At 250 512 hexahedra other amgsys settings did not reach 50 either (3 sweeps; most in a Newton
iteration, Krylov iterations in the step, Newton iterations, s): at most 6 entries per
interpolation row 55, 224, 6, 359 s; strength threshold 0.8: 57, 206, 5, 336 s (peak 2.06e9 B
each, as with the file's settings); two-stage extended+i interpolation on the aggressive level (`-pc_amgsys_agg_interp_type 2s-ext+i-mm`; at 25 600 hexahedra most 38 against 35) was stopped after 5 minutes still in the predictor's linear solve (about 50 s with multipass).

The 1 010 224-hexahedra row and the ones above were run before `-newton_ksp_target` (below); the
bound of 50 holds to 100 352 hexahedra on the whole blank (25 600: 35 with the option, 64
without) and to 9 600 on the quarter blank through 40 mm, not at 250 512 (54) nor at 1 010 224
(78 at most, in the last two Newton iterations, whose linear solves start from residuals
2e-5 and 5e-9 of the first); a step at 250 512 takes a third of the time it took. The step at 1 010 224 hexahedra is the first whole step at that size:
9 Newton iterations (|R| 1365, 312, 112, 107, 84, 28, 2.6, 0.022, 6.6e-6, 2.8e-9: four slow
iterations before the quadratic end, as contact spreads over 505 938 slave nodes), no cut, 48
minutes on the 2 shared cores; its peak resident size, sampled every 15 s and from
`-memory_view`, is that of the memory-only run (7.63 against 7.37 GiB).

**The last Newton iteration's linear solve: `-newton_ksp_target`.** The most Krylov iterations
of a step often fell in its last Newton iteration, which had the least to do: on the whole blank
of 25 600 hexahedra (1 rank, first step of 1 mm, `cases/solver_amgsys.opts` as it was) the solves
took 25 (the predictor's), 19, 30, 32, 35 and 64, the last from |R| = 1.08e-5 with the Newton
tolerance at 5.1e-6 (1e-9 of |R_0| = 5125): it reduced |R| by the full 1e-3 where a factor of 2
was enough (to 5.9e-9). `-newton_ksp_target η` (src/process/stepper.c) gives the linear solve of
Newton iteration k the relative tolerance max(`-ksp_rtol`, η tol / |R_k|), so only an iteration
that starts below η / `-ksp_rtol` times the tolerance (50 times for η = 0.05 and 1e-3) is
affected; both solver files set η = 0.05. The residual
BiCGStab measures (preconditioned) fell 2.5 to 5.5 times further than |R| did, hence η well
below 1:

| η | Krylov per solve, 25 600 hexahedra | in the step (most) | Newton its | final \|R\| / tol | step s |
|---|---|---|---|---|---|
| 0 (before) | 25, 19, 30, 32, 35, 64 | 180 (64) | 5 | 1e-3 | 49.0 |
| 0.02 | 25, 19, 30, 32, 35, 52 | 168 (52) | 5 | 9e-3 | 45.2 |
| 0.05 (the files) | 25, 19, 30, 32, 35, 22 | 138 (35) | 5 | 0.12 | 39.0 |
| 0.1 | 25, 19, 30, 32, 35, 18 | 134 (35) | 5 | 0.54 | 37.9 |
| 0.3 | 25, 19, 30, 32, 35, 17, 11 | 144 (35) | 6 (the fifth stopped above tol) | 0.24 | 40.4 |

At 100 352 hexahedra (1 rank, η = 0.05): 37, 24, 46, 45, 49, 21 (the last from 5.4e-6, tol 2.5e-6;
before 200 in the step), 185 in the step, 222 s, most 49 as before, in the fourth Newton
iteration (from 8.1e-3). At 250 512 (2 ranks) nothing changes: 41, 31, 25, 31, 42, 54, the last
from 8.8e-3, where a reduction by 1e-3 is still needed to reach the tolerance (1.5e-6). At
1 010 224 (2 ranks, the step run again with the option, 2026-11-24): the same solves up to the
last (59, 31, 51, 49, 45, 46, 37, 44, 78, the same residuals), the last 45 instead of 66 (from
6.6e-6, the tolerance 1.4e-6; |R| 1.2e-8 after it), 2 814 s for the step against 2 888 s; the
most is still 78, from 0.022. So the bound of 50 is limited by the
solves of the iterations before the last, from residuals 3e-6 to 2e-5 of the first (100 352:
3.3e-6, 250 512: 5.7e-6, 1 010 224: 1.6e-5), which sit at the contact zone's edge.

**The Krylov method.** One BiCGStab iteration applies the preconditioner twice, one GMRES
iteration once: in iterations BiCGStab looks better, in time GMRES is (the first step of 1 mm,
`cases/solver_amgsys.opts` with `-ksp_type` changed, 1 rank): at 25 600 hexahedra BiCGStab 138
Krylov iterations in the step (most 35), 39 s; BiCGStab(2) (`bcgsl`) 136 (most 38), 41 s;
GMRES(100) 224 (most 50), 30 s. At 100 352 GMRES(100) 250 (44, 28, 61, 61, 63, 37; most 63), 155 s
against BiCGStab's 185 (most 49), 222 s, at 1.114e9 against 1.008e9 B peak (the Krylov basis:
one vector of the unknowns per iteration, which at 1 010 224 hexahedra would add some
0.2 GiB per 100 000 hexahedra at 60 iterations). The files keep BiCGStab for the memory target;
GMRES is the faster choice where memory allows.
"""


def log(msg):
    print(f"[bench_million {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def event_time(out, name):
    """max time over the ranks of a -log_view event of the Solve stage (0 when absent)"""
    t = benchutil.log_event_time(out, name, "Solve")
    return t if t is not None else 0.0


def tag(p):
    return f"nc{p[0]}_nr{p[1]}_s{p[2]}_t{p[3]:g}_np{p[4]}" + ("_mem" if p[5] else "")


def rank_pids(pid):
    """the atrito processes under pid (itself, or the ranks that mpiexec started)"""
    out, todo = [], [pid]
    while todo:
        q = todo.pop()
        try:
            with open(f"/proc/{q}/comm") as f:
                if f.read().strip() == "atrito":
                    out.append(q)
            with open(f"/proc/{q}/task/{q}/children") as f:
                todo += [int(c) for c in f.read().split()]
        except (OSError, ValueError):
            pass
    return out


def vm_kb(pid, key):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        pass
    return 0


def run(binary, p, logdir, timeout, extra=()):
    """one run; beside its log, <tag>.ts (seconds since the start, then each line of output, so
    that a run stopped at the time limit still shows its time per solve) and <tag>.hwm (every 15 s:
    seconds, the ranks' peak and current resident sizes in kB, summed)"""
    nc, nr, steps, travel, ranks, mode = p
    cmd = [] if ranks == 1 else ["mpiexec", "--oversubscribe", "-n", str(ranks)]
    cmd += [binary, "-options_file", CASE, "-options_file", SOLVER, "-blank_core_cells", str(nc), "-blank_radial_cells", str(nr),
            "-blank_layers", str(LAYERS), "-tool_punch_motion", f"0,0,{travel:g}", "-load_steps", str(steps), "-load_dt_max", f"{1.0 / steps:.12g}",
            "-output_interval", "0", "-output_dir", os.path.join(logdir, "out_" + tag(p)),
            "-memory_view", "-memory_phases", "-log_view"] + (MEMORY_ONLY + ["-ksp_converged_reason", "-snes_monitor"] if mode else []) + list(extra)
    base = os.path.join(logdir, tag(p))
    path = base + ".log"
    t0 = time.monotonic()
    proc = subprocess.Popen(["nice"] + cmd, cwd=ROOT, env=benchutil.run_env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, start_new_session=True)
    done = threading.Event()

    def sample():
        with open(base + ".hwm", "w") as h:
            while not done.wait(15.0):
                pids = rank_pids(proc.pid)
                h.write(f"{time.monotonic() - t0:.0f} {sum(vm_kb(q, 'VmHWM') for q in pids)} {sum(vm_kb(q, 'VmRSS') for q in pids)}\n")
                h.flush()

    def stop():
        try:
            os.killpg(proc.pid, signal.SIGTERM)
        except OSError:
            pass

    sampler = threading.Thread(target=sample, daemon=True)
    sampler.start()
    timer = threading.Timer(timeout, stop)
    timer.start()
    with open(path, "w") as f, open(base + ".ts", "w") as ts:
        f.write("# " + " ".join(cmd) + "\n")
        for line in proc.stdout:
            f.write(line)
            ts.write(f"{time.monotonic() - t0:.1f} {line}")
            f.flush()
            ts.flush()
    proc.wait()
    timed_out = not timer.is_alive() and time.monotonic() - t0 >= timeout
    timer.cancel()
    done.set()
    sampler.join()
    with open(path, "a") as f:
        f.write(f"\n# exit {'timeout' if timed_out else proc.returncode} wall {time.monotonic() - t0:.1f} s\n")
    return path


def parse(path, p):
    with open(path) as f:
        out = f.read()
    nc, nr, steps, travel, ranks, mode = p
    rec = dict(point=p, ranks=ranks, travel=travel, memory_only=bool(mode))
    me, dn, mem = MESH_RE.search(out), DONE_RE.search(out), MEM_RE.search(out)
    rec["cells"] = int(me.group(2)) if me else 4 * (nc * nc + 2 * nc * nr) * LAYERS
    rec["vertices"] = int(me.group(1)) if me else None
    rec["steps"] = [dict(step=int(m.group(1)), time=float(m.group(2)), its=int(m.group(3)), krylov=int(m.group(4)), most=int(m.group(5)),
                         elapsed=float(m.group(7))) for m in STEP_RE.finditer(out)]
    rec["cuts"] = len(CUT_RE.findall(out))
    rec["phases"] = [(m.group(1), float(m.group(2)), int(m.group(3)) if m.group(3) else None) for m in PHASE_RE.finditer(out)]
    ex = re.search(r"^# exit (\S+) wall ([\d.]+) s", out, re.M)
    rec["exit"] = ex.group(1) if ex else "?"
    rec["wall"] = float(ex.group(2)) if ex else None
    rec["complete"] = bool(dn and mem)
    if dn:
        rec["newton"], rec["solve_s"] = int(dn.group(2)), float(dn.group(4))
    elif rec["steps"]:
        rec["newton"], rec["solve_s"] = sum(s["its"] for s in rec["steps"]), rec["steps"][-1]["elapsed"]
    if mem:
        rec["rss"] = float(mem.group(1))
    # the sidecars of run(): the linear solves and Newton iterations as they ended, the peak memory
    rec["solves"], rec["newton_done"], setup_t = [], 0, None
    if os.path.exists(path[:-4] + ".ts"):
        last, in_snes = None, False
        with open(path[:-4] + ".ts") as f:
            for line in f:
                t, _, text = line.partition(" ")
                t = float(t)
                if text.startswith("memory: after the problem setup"):
                    setup_t = last = t
                m = LSOLVE_RE.search(text)
                if m:
                    rec["solves"].append(dict(its=int(m.group(2)), converged=m.group(1) == "converged", newton=in_snes,
                                              seconds=t - last if last is not None else None))
                    last = t
                m = SNESMON_RE.match(text)
                if m:
                    in_snes = True  # the solves before a step's first Newton residual are the tangent predictor's
                if m and int(m.group(1)) > 0:
                    rec["newton_done"] += 1
                if STEP_RE.match(text) or text.startswith("step "):
                    in_snes = False
    rec["setup_s"] = setup_t
    if os.path.exists(path[:-4] + ".hwm"):
        with open(path[:-4] + ".hwm") as f:
            v = [int(l.split()[1]) for l in f if len(l.split()) == 3]
        if v and max(v) > 0:
            rec["hwm"] = 1024.0 * max(v)
    if rec["complete"] or (rec["memory_only"] and mem):
        fe, je = event_time(out, "SNESFunctionEval"), event_time(out, "SNESJacobianEval")
        pcs, ksp = event_time(out, "PCSetUp"), event_time(out, "KSPSolve")
        rec["split"] = dict(assembly=fe + je, pcsetup=pcs, krylov=max(ksp - pcs, 0.0))
    return rec


def fmt_gib(b):
    return f"{b / 2**30:.2f}"


def section(rows, timeout):
    L = [HEADING, "",
         benchutil.measured_by("bench_million.py", ROOT), "",
         f"The friction benchmark on the whole blank (`{CASE}`: analytic tools, penalties per unit area, Coulomb 0.15, "
         f"4 layers), with the iterative solver of `{SOLVER}` (BiCGStab, BoomerAMG with aggressive coarsening on the first level "
         "and 2 smoothing sweeps, `-ksp_rtol 1e-3`, the Jacobian assembled in hypre's format without its auxiliary assembly "
         "structure, no rigid-body modes), no field output. Peak resident set size as PETSc reports it (`-memory_view`, summed over the ranks); "
         "Krylov iterations from the progress line (`krylov N (most M)`: the step's total and the most in one Newton "
         "iteration; one BiCGStab iteration applies the matrix and the preconditioner twice); time per Newton iteration "
         "= the solve's time over its Newton iterations, split by `-log_view` into assembly (residuals and Jacobians, "
         "contact included), preconditioner setup (BoomerAMG's hierarchy) and Krylov iterations.", "",
         f"| hexahedra | unknowns (about) | ranks | travel mm | steps done | Newton its | cuts | Krylov its per Newton it, most | "
         f"peak RSS GiB | GiB per 100 000 hex | s per Newton it | assembly / PC setup / Krylov s per Newton it | run |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        n = r.get("newton") or 0
        most = max([s["most"] for s in r["steps"]] + [x["its"] for x in r["solves"] if x["newton"]], default=None)
        peak = r.get("rss", r.get("hwm"))
        per100 = fmt_gib(peak * 1e5 / r["cells"]) if peak else "–"
        rss = fmt_gib(peak) if peak else "–"
        sv = [x["seconds"] for x in r["solves"] if x["seconds"] is not None and x["newton"]]
        if r["memory_only"]:
            n = r["newton_done"] or (1 if r["solves"] else 0)
        if r["complete"] and n and not r["memory_only"]:
            spn = f"{r['solve_s'] / n:.1f}"
        elif sv:  # stopped: the mean time from one linear solve's end to the next (Jacobian, setup, Krylov)
            spn = f"{sum(sv) / len(sv):.0f} (from the timestamps)"
        else:
            spn = "–"
        if not n:
            n = r["newton_done"]
        if "split" in r and n:
            sp = r["split"]
            split = f"{sp['assembly'] / n:.1f} / {sp['pcsetup'] / n:.1f} / {sp['krylov'] / n:.1f}"
        else:
            split = "–"
        status = "memory only: first Newton iteration (no predictor), then stopped" if r["memory_only"] else "complete" if r["complete"] else (f"stopped at the {timeout:.0f} s limit" if r["exit"] == "timeout" else
                                                   f"stopped by hand after {r['wall'] / 60:.0f} min" if r["exit"] == "stopped" else f"exit {r['exit']}")
        unk = 3 * r["vertices"] if r["vertices"] else "–"
        L.append(f"| {r['cells']} | {unk} | {r['ranks']} | {r['travel']:g} | {len(r['steps'])} | {n} | {r['cuts']} | "
                 f"{most if most is not None else '–'} | {rss} | {per100} | {spn} | {split} | {status} |")
    L.append("")
    for r in rows:
        if not r["steps"]:
            continue
        L.append(f"Steps of the {r['cells']}-hexahedra run ({r['ranks']} rank{'s' if r['ranks'] > 1 else ''}): " + "; ".join(
            f"step {s['step']} at {s['time'] * r['travel']:.2f} mm: {s['its']} Newton its, Krylov {s['krylov']} (most {s['most']}), "
            f"{s['elapsed']:.0f} s elapsed" for s in r["steps"]) + ".")
        L.append("")
    for r in rows:
        sv = [x for x in r["solves"] if x["seconds"] is not None]
        if sv:
            L.append(f"Linear solves of the {r['cells']}-hexahedra run as they ended (the first one of a step is the tangent "
                     f"predictor's, then one per Newton iteration; {r['newton_done']} Newton iteration{'s' if r['newton_done'] != 1 else ''} done): " + "; ".join(
                         f"{x['its']} Krylov its{'' if x['converged'] else ' (not converged)'}{'' if x['newton'] else ' (tangent predictor)'} in {x['seconds']:.0f} s" for x in sv) +
                     f". Setup (mesh to Jacobian) {r['setup_s']:.0f} s." + (
                         "" if r["complete"] else f" Peak resident size from the ranks' VmHWM (sampled every 15 s): {fmt_gib(r['hwm'])} GiB." if r.get("hwm") else ""))
            L.append("")
    for r in rows:
        if r["phases"]:
            L.append(f"Memory after the setup phases, {r['cells']} hexahedra (resident, summed over the ranks): " + "; ".join(
                f"{ph} {mib / 1024:.2f} GiB" + (f" (Jacobian {nz} nonzeros)" if nz else "") for ph, mib, nz in r["phases"]) + ".")
            L.append("")
    ok = [r for r in rows if "rss" in r]
    big = max(rows, key=lambda r: r["cells"]) if rows else None
    if big:
        most = max([s["most"] for s in big["steps"]] + [x["its"] for x in big["solves"] if x["newton"]], default=None)
        peak = big.get("rss", big.get("hwm"))
        per = peak * 1e5 / big["cells"] / 2**30 if peak else None
        if big["memory_only"]:
            L.append(f"Against the targets ({big['cells']} hexahedra): memory {'met' if per is not None and per <= TARGET_GIB else 'not met'} "
                     f"({'%.2f' % per if per is not None else 'no'} GiB per 100 000 hexahedra against {TARGET_GIB}); a memory-only run: "
                     f"its one Newton iteration took {most if most is not None else '–'} Krylov iterations (the bound of {TARGET_KRYLOV} "
                     "is judged on whole steps, above).")
            L.append("")
        else:
            L.append(f"Against the targets ({big['cells']} hexahedra): memory {'met' if per is not None and per <= TARGET_GIB else 'not met'} "
                     f"({'%.2f' % per if per is not None else 'no'} GiB per 100 000 hexahedra against {TARGET_GIB}); Krylov iterations "
                     f"{'met' if most is not None and most <= TARGET_KRYLOV else 'not met'} (most in one Newton iteration "
                     f"{most if most is not None else '–'} against {TARGET_KRYLOV}); {len(big['steps'])} steps to "
                     f"{(big['steps'][-1]['time'] * big['travel']) if big['steps'] else 0:.2f} mm.")
            L.append("")
    L.append(NOTES)
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--point", action="append", default=[], help="NC,NR,STEPS,TRAVEL,RANKS (repeatable)")
    ap.add_argument("--timeout", type=float, default=3000.0, help="seconds per run")
    ap.add_argument("--logdir", default=None, help="keep the logs here")
    ap.add_argument("--reuse", action="store_true", help="read the logs in --logdir instead of running")
    ap.add_argument("--extra", default="", help="more options for every run (e.g. -snes_monitor -ksp_converged_reason to follow a long run)")
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "notes", "performance-log.md"))
    ap.add_argument("--solver", default=SOLVER, help=f"the solver's options file (default {SOLVER}); the section's text describes the default")
    a = ap.parse_args()
    globals()["SOLVER"] = a.solver
    points = []
    for s in a.point:
        v = s.split(",")
        if len(v) not in (5, 6) or (len(v) == 6 and v[5] != "m"):
            sys.exit(f"--point {s}: give NC,NR,STEPS,TRAVEL,RANKS[,m]")
        points.append((int(v[0]), int(v[1]), int(v[2]), float(v[3]), int(v[4]), "m" if len(v) == 6 else ""))
    points = points or POINTS
    if a.reuse and not a.logdir:
        sys.exit("--reuse needs --logdir")
    logdir = a.logdir or tempfile.mkdtemp(prefix="bench_million_")
    os.makedirs(logdir, exist_ok=True)
    rows = []
    try:
        binary = None if a.reuse else benchutil.build_and_snapshot(ROOT, logdir, "bench_million", log)
        for p in points:
            path = os.path.join(logdir, tag(p) + ".log")
            if not a.reuse:
                log(f"running {tag(p)} ({4 * (p[0] ** 2 + 2 * p[0] * p[1]) * LAYERS} hexahedra)")
                run(binary, p, logdir, a.timeout, a.extra.split())
            if not os.path.exists(path):
                log(f"{tag(p)}: no log")
                continue
            rec = parse(path, p)
            log(f"{rec['cells']} hexahedra np={p[4]}: {len(rec['steps'])} steps, peak RSS "
                f"{fmt_gib(rec['rss']) + ' GiB' if 'rss' in rec else '?'}, exit {rec['exit']}")
            rows.append(rec)
    finally:
        if not a.logdir:
            shutil.rmtree(logdir, ignore_errors=True)
    benchutil.write_doc_section(a.output, HEADING, section(rows, a.timeout), keep_written=True)
    log(f"wrote {HEADING!r} to {a.output}")


if __name__ == "__main__":
    main()
