#!/usr/bin/env bash
# Integration tests of the solver paths, at 1 and 2 ranks. Each check prints "ok - ..." or
# "not ok - ...".
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out solver)

# 1. uniaxial tension to 30 % strain against the closed form, at 1 and 2 ranks
for np in 1 2; do
  atrito $np tension$np -options_file cases/tension_bar.opts &&
    $PY tests/check_tension.py "$OUT/tension$np/history.csv" pull_fx 1 10 3 $SWIFT 1e-6
done
compare "$OUT/tension1/history.csv" "$OUT/tension2/history.csv" 8 "tension bar: np=1 and np=2 (METIS) histories"

# 2. the fields of the tension run: valid HDF5/XDMF, end displacement and plastic strain exact
$PY tests/check_fields.py "$OUT/tension2" -q >/dev/null && ok "tension bar fields.h5 and fields.xmf valid (np=2)" || not_ok "tension bar fields invalid"
pycheck tension_fields "$OUT/tension2/fields.h5"

# 3. -snes_test_jacobian on a small plastic problem, F-bar and standard elements
for fbar in 1 0; do
  el=$([ $fbar = 1 ] && echo F-bar || echo standard)
  atrito 1 jac$fbar -options_file cases/clamped_beam.opts -box_cells 3,1,2 -load_steps 3 -output_interval 0 -fe_fbar $fbar -snes_test_jacobian &&
    pycheck snes_test_jacobian "$OUT/jac$fbar.log" 6 1e-6 "plastic, $el element"
done

# 4. the same non-homogeneous cases at 1 and 2 ranks, METIS and simple partitions: same history
atrito 1 beam1 -options_file cases/clamped_beam.opts -output_interval 0
atrito 2 beam2 -options_file cases/clamped_beam.opts -output_interval 0
atrito 2 beam2s -options_file cases/clamped_beam.opts -output_interval 0 -partition simple
compare "$OUT/beam1/history.csv" "$OUT/beam2/history.csv" 8 "clamped beam: np=1 and np=2 (METIS)"
compare "$OUT/beam1/history.csv" "$OUT/beam2s/history.csv" 8 "clamped beam: np=1 and np=2 (simple partition)"
# the two LU paths: MUMPS with the METIS nested-dissection ordering (default) and MUMPS's own
# ordering through PETSc's interface; the default analyses the pattern once per run
atrito 2 beam2m -options_file cases/clamped_beam.opts -output_interval 0 -lu_ordering mumps
compare "$OUT/beam2/history.csv" "$OUT/beam2m/history.csv" 10 "clamped beam (np=2): -lu_ordering nd and -lu_ordering mumps"
atrito 2 beam2v -options_file cases/clamped_beam.opts -output_interval 0 -load_steps 4 -ksp_view
v=$(grep -c "LU by MUMPS, METIS nested-dissection ordering" "$OUT/beam2v.log"); a=$(grep -o "unknowns; [0-9]* analyses" "$OUT/beam2v.log" | sort -u | tr '\n' ' ')
s=$(grep -o "^step *[0-9]*" "$OUT/beam2v.log" | wc -l)
[ "$v" -ge 1 ] && [ "$a" = "unknowns; 1 analyses " ] && [ "$s" -ge 4 ] && ok "-ksp_view (np=2): LU with the METIS ordering, one analysis for all $s steps ($v solves)" || not_ok "-ksp_view: '$v' views, analyses '$a', $s steps"
# reproducibility at 2 ranks: MUMPS's parallel factorisation assembles in the order its messages
# arrive, so its last digits vary from run to run (doc/options.md); SuperLU_dist gives the same
# digits every time: two runs of the seed case with contact, bit for bit
for k in a b; do atrito 2 sdist_$k -options_file cases/hemisphere_frictionless.opts -output_interval 0 -pc_factor_mat_solver_type superlu_dist; done
[ -s "$OUT/sdist_a/contact.csv" ] && cmp -s "$OUT/sdist_a/contact.csv" "$OUT/sdist_b/contact.csv" && cmp -s "$OUT/sdist_a/history.csv" "$OUT/sdist_b/history.csv" &&
  ok "-pc_factor_mat_solver_type superlu_dist (np=2): two runs of the seed case give the same history and contact.csv, bit for bit" ||
  not_ok "superlu_dist (np=2): two runs differ"
atrito 1 blank1 -options_file cases/blank_point.opts -output_interval 3
atrito 2 blank2 -options_file cases/blank_point.opts -output_interval 3
compare "$OUT/blank1/history.csv" "$OUT/blank2/history.csv" 8 "quarter blank (O-grid): np=1 and np=2 (METIS)"
grep -q "cells per rank: [1-9][0-9]* [1-9][0-9]*$" "$OUT/blank2.log" && ok "partition report: $(grep -o 'cells per rank.*' "$OUT/blank2.log")" || not_ok "no cells-per-rank report"
$PY tests/check_fields.py "$OUT/blank2" -q >/dev/null && pycheck blank_fields "$OUT/blank2/fields.h5"

# 5. the three mesh sources agree: box, Gmsh file and .inp deck of the same two hexahedra
common="-bc_names fix,pull -bc_fix_components x,y,z -bc_pull_components x -bc_pull_values 0.2 -load_steps 4 -output_interval 0"
atrito 1 src_box -mesh_type box -box_upper 2,1,1 -box_cells 2,1,1 $common -bc_fix_set xmin -bc_pull_set xmax
atrito 2 src_msh -mesh_file tests/data/two_hex.msh $common -bc_fix_set left -bc_pull_set right
atrito 1 src_inp -mesh_file tests/data/two_hex.inp $common -bc_fix_set Left -bc_pull_set Right
for s in msh inp; do
  compare "$OUT/src_box/history.csv" "$OUT/src_$s/history.csv" 10 "two hexahedra: box and $s mesh give the same history"
done

# 6. failed steps are retried smaller, easy steps grow again, and a run that cannot go on stops
#    with a message naming the cause while its history stays whole and valid
tension_after() { # tension_after NAME WHAT: the closed-form check of run NAME, its line prefixed with WHAT
  $PY tests/check_tension.py "$OUT/$1/history.csv" pull_fx 1 10 3 $SWIFT 1e-6 | sed "s/^\(n*o*t* *ok\) - /\1 - $2: /"
}
atrito 1 cut_newton -options_file cases/tension_bar.opts -load_steps 1 -snes_max_it 2 -output_interval 0 &&
  n=$(grep -c "retrying with increment" "$OUT/cut_newton.log") && g=$(grep -c "did not converge in the allowed iterations" "$OUT/cut_newton.log") &&
  [ "$n" -ge 1 ] && [ "$g" -ge 1 ] && tension_after cut_newton "after $n cuts (Newton iteration limit)" ||
  not_ok "Newton failure was not retried"
atrito 1 cut_stall -options_file cases/tension_bar.opts -load_steps 1 -newton_stall_its 1 -newton_stall_factor 1e-3 -output_interval 0 &&
  n=$(grep -c "Newton stalled (|R| .* did not fall below 0.001 times its value 1 iterations earlier, -newton_stall_its); retrying" "$OUT/cut_stall.log") && [ "$n" -ge 1 ] &&
  tension_after cut_stall "after $n cuts (Newton stalled)" ||
  not_ok "a stalled Newton solve was not cut"
atrito 1 cut_retmap -options_file cases/tension_bar.opts -load_steps 1 -material_return_maxit 3 -output_interval 0 &&
  n=$(grep -c "the local return map did not converge (element id [0-9]*); retrying" "$OUT/cut_retmap.log") && [ "$n" -ge 1 ] &&
  tension_after cut_retmap "after $n cuts (return map failure)" ||
  not_ok "return-map failure was not retried"
atrito_rc 2 cut_fail -options_file cases/tension_bar.opts -load_steps 2 -bc_pull_values -10.5 -load_max_cuts 3 -output_interval 1
pycheck stopped_run "$OUT/cut_fail" "$RC" "impossible compression stops cleanly (np=2)"
alone_ok 2 cut_fail "impossible compression" -options_file cases/tension_bar.opts -load_steps 2 -bc_pull_values -10.5 -load_max_cuts 3 -output_interval 1

# 7. a NaN in the residual (fault injection): retried with a smaller increment; with no cut
#    allowed, the run stops naming the cause and the load
atrito 1 nan -options_file cases/tension_bar.opts -fault_nan_residual_at 0.5 -output_interval 0 &&
  grep -q "NaN or Inf in the residual; retrying" "$OUT/nan.log" &&
  tension_after nan "after a NaN residual, retried" ||
  not_ok "a NaN residual was not retried"
atrito_rc 2 nanfail -options_file cases/tension_bar.opts -fault_nan_residual_at 0.5 -load_max_cuts 0 -output_interval 0
msg=$(grep -o "atrito: error: step [0-9]* failed at load [0-9.]* .*NaN or Inf in the residual.*" "$OUT/nanfail.log" | head -1)
[ $RC -ne 0 ] && [ $RC -lt 124 ] && [ -n "$msg" ] && ok "a NaN with no cut allowed stops the run (np=2, exit $RC): ${msg:0:110}" || not_ok "NaN final message (exit $RC)"
alone_ok 2 nanfail "a NaN with no cut allowed" -options_file cases/tension_bar.opts -fault_nan_residual_at 0.5 -load_max_cuts 0 -output_interval 0

# 8. the iterative solver path: GMRES with algebraic multigrid and the rigid-body near-null
#    space, at 1 and 2 ranks, against the direct solver's history
GAMG="-ksp_type gmres -pc_type gamg -ksp_rtol 1e-12 -ksp_max_it 400"
atrito 1 gamg1 -options_file cases/clamped_beam.opts -output_interval 0 $GAMG
atrito 2 gamg2 -options_file cases/clamped_beam.opts -output_interval 0 $GAMG
compare "$OUT/beam1/history.csv" "$OUT/gamg1/history.csv" 8 "clamped beam: GMRES+GAMG (np=1) against LU"
compare "$OUT/beam1/history.csv" "$OUT/gamg2/history.csv" 8 "clamped beam: GMRES+GAMG (np=2) against LU"

# 9. the large-sheet solver (cases/solver_amg_sheet.opts: BiCGStab + BoomerAMG, the Jacobian in
#    hypre's format) on the whole blank with friction, at 1 and 2 ranks, against LU: the same
#    histories (the Newton tolerances decide, not the linear solver's), the Krylov iterations per
#    step on the progress line and at most 50 in any Newton iteration; Newton's tolerance is
#    -snes_rtol alone (-newton_force_tol 0), so that the histories compare the solvers to 6 digits
DISK="-newton_force_tol 0 -options_file cases/hemisphere_friction_disk.opts -blank_core_cells 4 -blank_radial_cells 10 -blank_layers 2 -tool_punch_motion 0,0,3 -load_steps 3 -load_dt_max 0.34 -output_interval 0"
atrito 1 disk_lu $DISK
for np in 1 2; do
  atrito $np disk_amg$np $DISK -options_file cases/solver_amg_sheet.opts &&
    compare "$OUT/disk_lu/history.csv" "$OUT/disk_amg$np/history.csv" 6 "whole blank with friction: BiCGStab+BoomerAMG (np=$np) against LU"
  most=$(grep -o "krylov [0-9]* (most [0-9]*)" "$OUT/disk_amg$np.log" | awk '{gsub(/\)/,"",$4); v = $4 + 0; if (v > m) m = v} END {print m + 0}')
  n=$(grep -c "^step .* krylov [0-9]* (most [0-9]*)" "$OUT/disk_amg$np.log")
  [ "$n" -ge 3 ] && [ "$most" -ge 1 ] && [ "$most" -le 50 ] && ok "Krylov iterations on the progress line of every step ($n steps, np=$np), at most $most per Newton iteration" ||
    not_ok "Krylov iterations: $n step lines, most $most (np=$np)"
done
! grep -q "krylov" "$OUT/disk_lu.log" && ok "LU runs: no Krylov count on the progress line" || not_ok "LU run prints a Krylov count"

# 10. the quarter blank (symmetry planes: rows no longer in threes, block size 1):
#     cases/solver_amgsys.opts (-pc_type amgsys, src/solver/amg.c: BoomerAMG told each row's
#     component) at 1 and 2 ranks against LU, at
#     most 50 Krylov iterations per Newton iteration, fewer than PCHYPRE's (which mixes the
#     components there); the Jacobian in hypre's format and in AIJ (converted at each setup)
QUARTER="-options_file cases/hemisphere_friction_fine.opts -blank_core_cells 4 -blank_radial_cells 10 -blank_layers 2 -tool_punch_motion 0,0,3 -load_steps 3 -load_dt_max 0.34 -output_interval 0"
most_of() { grep -o "krylov [0-9]* (most [0-9]*)" "$1" | awk '{gsub(/\)/,"",$4); v = $4 + 0; if (v > m) m = v} END {print m + 0}'; }
atrito 1 quarter_lu $QUARTER
for np in 1 2; do
  atrito $np quarter_sys$np $QUARTER -options_file cases/solver_amgsys.opts &&
    compare "$OUT/quarter_lu/history.csv" "$OUT/quarter_sys$np/history.csv" 6 "quarter blank with friction: BiCGStab + amgsys (np=$np) against LU"
done
atrito 1 quarter_hypre $QUARTER -options_file cases/solver_amg_sheet.opts
atrito 1 quarter_aij $QUARTER -options_file cases/solver_amgsys.opts -assembly_mat_type aij
compare "$OUT/quarter_lu/history.csv" "$OUT/quarter_aij/history.csv" 6 "quarter blank: amgsys on an AIJ Jacobian (converted) against LU"
m1=$(most_of "$OUT/quarter_sys1.log"); m2=$(most_of "$OUT/quarter_sys2.log"); mh=$(most_of "$OUT/quarter_hypre.log")
[ "$m1" -ge 1 ] && [ "$m1" -le 50 ] && [ "$m2" -ge 1 ] && [ "$m2" -le 50 ] && [ "$m1" -lt "$mh" ] &&
  ok "quarter blank: amgsys at most $m1 (np=1) and $m2 (np=2) Krylov iterations per Newton iteration, PCHYPRE $mh" ||
  not_ok "quarter blank: amgsys most $m1 (np=1), $m2 (np=2), PCHYPRE $mh"

# 11. -newton_ksp_target (0.05 in cases/solver_amg_sheet.opts and solver_amgsys.opts): a Newton
#     iteration's linear solve stops at that fraction of the Newton tolerance when it gets there
#     before -ksp_rtol, so the last iteration does not reduce an |R| already near the tolerance by
#     another 1e-3. The whole blank of section 9 against the same run with the option off: fewer
#     Krylov iterations in all (the first step's last solve), no more Newton iterations, and both
#     within the tolerance of LU's history
sum_of() { grep -o "krylov [0-9]* (most" "$1" | awk '{s += $2} END {print s + 0}'; }
newton_of() { sed -n 's/^done: .* steps, \([0-9]*\) Newton iterations.*/\1/p' "$1"; }
atrito 1 disk_target0 $DISK -options_file cases/solver_amg_sheet.opts -newton_ksp_target 0 &&
  compare "$OUT/disk_lu/history.csv" "$OUT/disk_target0/history.csv" 6 "whole blank: BiCGStab+BoomerAMG with -newton_ksp_target 0 against LU"
k1=$(sum_of "$OUT/disk_amg1.log"); k0=$(sum_of "$OUT/disk_target0.log")
n1=$(newton_of "$OUT/disk_amg1.log"); n0=$(newton_of "$OUT/disk_target0.log")
[ -n "$n1" ] && [ -n "$n0" ] && [ "$k1" -ge 1 ] && [ "$k1" -lt "$k0" ] && [ "$n1" -le "$n0" ] &&
  ok "-newton_ksp_target 0.05: $k1 Krylov iterations in $n1 Newton iterations, against $k0 in $n0 with the option off" ||
  not_ok "-newton_ksp_target 0.05: $k1 Krylov iterations in ${n1:-?} Newton iterations, off: $k0 in ${n0:-?}"

# 12. amgsys and PCHYPRE on the whole blank (block size 3, every node with its three unknowns)
#     differ in the smoothing order only: with three sweeps, amgsys in CF order takes PCHYPRE's
#     Krylov iterations step for step, and PCHYPRE in natural order (-pc_hypre_boomeramg_no_CF)
#     amgsys's (src/solver/amg.c)
kry_of() { grep -o "krylov [0-9]* (most [0-9]*)" "$1" | tr '\n' ' '; }
atrito 1 disk_sys_cf $DISK -options_file cases/solver_amgsys.opts -pc_amgsys_relax_order CF
atrito 1 disk_hyp3 $DISK -options_file cases/solver_amg_sheet.opts -pc_hypre_boomeramg_grid_sweeps_all 3
atrito 1 disk_sys $DISK -options_file cases/solver_amgsys.opts
atrito 1 disk_hyp3_nocf $DISK -options_file cases/solver_amg_sheet.opts -pc_hypre_boomeramg_grid_sweeps_all 3 -pc_hypre_boomeramg_no_CF
a=$(kry_of "$OUT/disk_sys_cf.log"); b=$(kry_of "$OUT/disk_hyp3.log"); c=$(kry_of "$OUT/disk_sys.log"); d=$(kry_of "$OUT/disk_hyp3_nocf.log")
[ -n "$a" ] && [ "$a" = "$b" ] && [ -n "$c" ] && [ "$c" = "$d" ] && [ "$a" != "$c" ] &&
  ok "whole blank: amgsys -pc_amgsys_relax_order CF = PCHYPRE ($a), natural = PCHYPRE -pc_hypre_boomeramg_no_CF ($c)" ||
  not_ok "whole blank: amgsys CF '$a' against PCHYPRE '$b'; natural '$c' against PCHYPRE no_CF '$d'"

# 13. cases/solver_amgsys_fast.opts (one sweep of the symmetric smoother, GMRES(100), the Jacobian
#     by coordinate assembly into hypre's format: tuned for the time per Newton iteration rather
#     than the Krylov iterations, doc/notes/performance-log.md): the quarter blank of section 10 at 1 and 2
#     ranks against LU; every option of the file read (no "never used" warning), and the Krylov
#     counts not those of cases/solver_amgsys.opts
for np in 1 2; do
  atrito $np quarter_fast$np $QUARTER -options_file cases/solver_amgsys_fast.opts &&
    compare "$OUT/quarter_lu/history.csv" "$OUT/quarter_fast$np/history.csv" 6 "quarter blank with friction: GMRES + amgsys, one sweep, COO into hypre (np=$np) against LU"
done
f=$(kry_of "$OUT/quarter_fast1.log"); s=$(kry_of "$OUT/quarter_sys1.log")
[ -n "$f" ] && [ "$f" != "$s" ] && ! grep -q "never used" "$OUT/quarter_fast1.log" "$OUT/quarter_fast2.log" &&
  ok "quarter blank, cases/solver_amgsys_fast.opts: every option read, Krylov iterations $f (solver_amgsys.opts: $s)" ||
  not_ok "cases/solver_amgsys_fast.opts: Krylov '$f' against solver_amgsys.opts '$s', or an option never used"

# 14. what -pc_amgsys_relax_type 3 is (src/solver/amg.c, doc/options.md): hypre sets the type on
#     both legs of the V-cycle, one forward pass per sweep going down and going up, so amgsys
#     takes PCHYPRE's Krylov iterations with the forward type on all legs, not those with the
#     backward type going up
atrito 1 disk_sys_r3 $DISK -options_file cases/solver_amgsys.opts -pc_amgsys_relax_type 3
atrito 1 disk_hyp_fwd $DISK -options_file cases/solver_amg_sheet.opts -pc_hypre_boomeramg_grid_sweeps_all 3 -pc_hypre_boomeramg_no_CF -pc_hypre_boomeramg_relax_type_all SOR/Jacobi
atrito 1 disk_hyp_fb $DISK -options_file cases/solver_amg_sheet.opts -pc_hypre_boomeramg_grid_sweeps_all 3 -pc_hypre_boomeramg_no_CF -pc_hypre_boomeramg_relax_type_down SOR/Jacobi -pc_hypre_boomeramg_relax_type_up backward-SOR/Jacobi
a=$(kry_of "$OUT/disk_sys_r3.log"); b=$(kry_of "$OUT/disk_hyp_fwd.log"); c=$(kry_of "$OUT/disk_hyp_fb.log")
[ -n "$a" ] && [ "$a" = "$b" ] && [ -n "$c" ] && [ "$a" != "$c" ] &&
  ok "whole blank: amgsys relax type 3 = PCHYPRE forward hybrid Gauss-Seidel on every leg ($a), not backward going up ($c)" ||
  not_ok "whole blank: amgsys relax type 3 '$a' against PCHYPRE forward on all legs '$b' and backward going up '$c'"

# 15. the Jacobian by coordinate assembly into hypre's format (cases/solver_amgsys_fast.opts:
#     PETSc's MATHYPRE with an AIJ matrix sharing its values, src/solver/problem.c):
#     -snes_test_jacobian with friction (block_sphere: sticking and slipping nodes), and on the
#     whole blank at 2 ranks the same history as MatSetValues into hypre's format
atrito 1 jac_hypre_coo -options_file cases/block_sphere.opts -output_interval 0 -box_cells 4,4,1 -options_file cases/solver_amgsys_fast.opts -snes_test_jacobian &&
  pycheck snes_test_jacobian "$OUT/jac_hypre_coo.log" 10 1e-5 "the Jacobian by COO into hypre's format, with contact on a sphere" --contact "$OUT/jac_hypre_coo"
TJ="-options_file cases/hemisphere_friction_disk.opts -blank_core_cells 2 -blank_radial_cells 5 -blank_layers 1 -tool_punch_motion 0,0,2 -load_steps 2 -load_dt_max 0.5 -output_interval 0"
atrito 2 hypre_coo2 $TJ -options_file cases/solver_amgsys_fast.opts
atrito 2 hypre_msv2 $TJ -options_file cases/solver_amgsys_fast.opts -assembly_coo 0
compare "$OUT/hypre_msv2/history.csv" "$OUT/hypre_coo2/history.csv" 6 "whole blank (np=2): the Jacobian by COO into hypre's format against MatSetValues into it"

# 16. the sheet's coarse space (cases/solver_amgsys_sheet.opts: amgsys with plate-like modes on a
#     grid of 4 mm after each V-cycle, src/solver/sheetcoarse.c): the quarter blank of section 10
#     (symmetry planes: single components removed) at 1 and 2 ranks against LU; the whole blank
#     of section 9 against LU, in fewer Krylov iterations than cases/solver_amgsys.opts (each
#     step's most) and at most half its total; every option of the file read
for np in 1 2; do
  atrito $np quarter_sheet$np $QUARTER -options_file cases/solver_amgsys_sheet.opts &&
    compare "$OUT/quarter_lu/history.csv" "$OUT/quarter_sheet$np/history.csv" 6 "quarter blank with friction: BiCGStab + amgsys with the sheet's coarse space (np=$np) against LU"
done
atrito 2 disk_sheet2 $DISK -options_file cases/solver_amgsys_sheet.opts &&
  compare "$OUT/disk_lu/history.csv" "$OUT/disk_sheet2/history.csv" 6 "whole blank with friction: amgsys with the sheet's coarse space (np=2) against LU"
ms=$(most_of "$OUT/quarter_sheet1.log"); mq=$(most_of "$OUT/quarter_sys1.log"); md=$(most_of "$OUT/disk_sheet2.log"); mo=$(most_of "$OUT/disk_sys.log")
ts=$(sum_of "$OUT/disk_sheet2.log"); to=$(sum_of "$OUT/disk_sys.log")
[ "$ms" -ge 1 ] && [ "$ms" -lt "$mq" ] && [ "$md" -ge 1 ] && [ "$md" -lt "$mo" ] && [ $((2 * ts)) -le "$to" ] && ! grep -q "never used" "$OUT/quarter_sheet1.log" "$OUT/disk_sheet2.log" &&
  ok "the sheet's coarse space: at most $ms Krylov iterations per Newton iteration on the quarter blank (without: $mq), $md on the whole blank (without: $mo), $ts in all there (without: $to)" ||
  not_ok "the sheet's coarse space: most $ms (quarter; without $mq), $md (whole; without $mo), total $ts (without $to), or an option never used"

# 17. amgsys with force-driven tools (src/solver/amg.c, BorderSetUp: the tools' unknowns
#     eliminated around the V-cycle through their Schur complement): the holder pressed by a force
#     on a sheet pulled across a die (cases/forcetool_holder.opts) with cases/solver_process.opts
#     at 1 and 2 ranks against LU; -ksp_view names the border
FT="-options_file cases/forcetool_holder.opts -output_interval 0"
atrito 1 ft_lu $FT
for np in 1 2; do
  atrito $np ft_sys$np $FT -options_file cases/solver_process.opts &&
    compare "$OUT/ft_lu/history.csv" "$OUT/ft_sys$np/history.csv" 6 "force-driven holder: BiCGStab + amgsys bordered by the holder's unknowns (np=$np) against LU"
done
atrito 2 ft_view $FT -options_file cases/solver_process.opts -load_steps 2 -ksp_view &&
  grep -q "bordered by 3 force-driven tool unknowns" "$OUT/ft_view.log" && ok "-ksp_view (np=2): amgsys bordered by the holder's 3 unknowns" ||
  not_ok "-ksp_view: no border named"
# 17b. the Jacobian bordered by the tools' unknowns (src/solver/bordered.c: hypre's mesh block and
#      the border as vectors, cases/solver_process.opts) against the same solver on an AIJ
#      Jacobian, whose mesh block amgsys copies: the same operator and preconditioner, the
#      products' sums in another order
atrito 2 ft_aij2 $FT -options_file cases/solver_process.opts -assembly_mat_type aij &&
  compare "$OUT/ft_aij2/history.csv" "$OUT/ft_sys2/history.csv" 9 "force-driven holder, amgsys (np=2): the bordered hypre Jacobian against an AIJ one"
grep -q "bordered Jacobian: the mesh block (hypre" "$OUT/ft_view.log" && ok "-ksp_view (np=2): the operator is the bordered Jacobian" || not_ok "-ksp_view: the bordered Jacobian not named"
