#!/usr/bin/env bash
# User materials (-material_type umat) in whole runs: the Fortran J2 UMAT (bin/umat_j2.so, from
# tests/umat_j2.f) against the built-in J2 in uniaxial tension, simple shear and a short contact
# run; -snes_test_jacobian with the UMAT in the plastic regime; bad input (missing library,
# missing symbol, a PNEWDT cut, a NaN stress) with the C UMATs of bin/umat_ctest.so.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out umat)
ATRITO_TIMEOUT=300
UJ2="-material_type umat -material_umat bin/umat_j2.so -material_umat_nstatev 1 -material_umat_statev_ep 1"
SWIFT_PROPS="-material_umat_props 69004,0.3,589,1e-4,0.216"

# 1. uniaxial tension to 30 %: proportional loading, the two formulations coincide
atrito 1 tension_j2 -options_file cases/tension_bar.opts -output_interval 0 &&
  atrito 1 tension_umat -options_file cases/tension_bar.opts -output_interval 0 $UJ2 $SWIFT_PROPS &&
  compare "$OUT/tension_j2/history.csv" "$OUT/tension_umat/history.csv" 8 "tension bar to 30 %: Fortran J2 UMAT and built-in J2 histories"
[ -f "$OUT/tension_umat/history.csv" ] && $PY tests/check_tension.py "$OUT/tension_umat/history.csv" pull_fx 1 10 3 $SWIFT 1e-6

# 2. simple shear of a 1 x 1 x 0.25 slab to shear 1.5 (top face moved by 1.5 along x, base fixed,
#    sides free): rotating principal axes. The additive corotational update differs from the
#    exponential map at second order (elastic strain sigma_y/E ~ 5e-3 times the rotation):
#    measured 2e-6 on the shear force and 4e-5 on the normal force (itself a second-order
#    effect), 1e-6 at the material point (tests/test_umat.c): 4 digits.
SHEAR="-mesh_type box -box_lower 0,0,0 -box_upper 1,1,0.25 -box_cells 2,2,2 -bc_names base,top -bc_base_set zmin -bc_base_components x,y,z -bc_top_set zmax -bc_top_components x,y,z -bc_top_values 0.375,0,0 -load_steps 15 -output_interval 0"
atrito 1 shear_j2 $SHEAR -material_hardening swift &&
  atrito 1 shear_umat $SHEAR $UJ2 $SWIFT_PROPS &&
  compare "$OUT/shear_j2/history.csv" "$OUT/shear_umat/history.csv" 4 "simple shear to 1.5: Fortran J2 UMAT and built-in J2 histories"

# 3. a short contact run: block and sphere (elastic, E = 1000), 4 steps, at 2 ranks
atrito 2 sphere_j2 -options_file cases/block_sphere.opts -load_max_steps 4 -output_interval 0 >/dev/null 2>&1 || true
atrito 2 sphere_umat -options_file cases/block_sphere.opts -load_max_steps 4 -output_interval 0 $UJ2 -material_umat_props 1000,0.3,1e9,0 >/dev/null 2>&1 || true
if [ -s "$OUT/sphere_j2/contact.csv" ] && [ -s "$OUT/sphere_umat/contact.csv" ]; then
  compare "$OUT/sphere_j2/contact.csv" "$OUT/sphere_umat/contact.csv" 3 "block and sphere, 4 steps at np=2: Fortran J2 UMAT (elastic) and built-in J2 contact histories"
else
  not_ok "block and sphere with the UMAT: no contact history"; tail -n 3 "$OUT/sphere_umat.log" | indent
fi

# 4. -snes_test_jacobian with the UMAT, plastic
atrito 1 jac -options_file cases/clamped_beam.opts -box_cells 3,1,2 -load_steps 3 -output_interval 0 $UJ2 $SWIFT_PROPS -snes_test_jacobian &&
  pycheck snes_test_jacobian "$OUT/jac.log" 6 1e-6 "Fortran J2 UMAT, plastic"

# 5. bad input: one-line errors, a cut
bad() { # bad NAME EXPECT ARGS...: a one-line "atrito: error" containing EXPECT, non-zero exit, no crash
  local name=$1 expect=$2; shift 2
  atrito_rc 1 "$name" "$@"
  local n; n=$(grep -c '^atrito: error' "$OUT/$name.log")
  if [ "$RC" -ne 0 ] && [ "$RC" -lt 124 ] && [ "$n" -eq 1 ] && grep -qF -- "$expect" "$OUT/$name.log"; then
    ok "$name: $(grep '^atrito: error' "$OUT/$name.log" | cut -c1-160)"
  else
    not_ok "$name: expected '$expect' (exit $RC, $n error lines)"; tail -n 5 "$OUT/$name.log" | indent
  fi
}
SMALL="-options_file cases/tension_bar.opts -box_cells 2,1,1 -load_steps 2 -output_interval 0"
bad nolib "-material_umat bin/no_such.so: cannot load the library" $SMALL -material_type umat -material_umat bin/no_such.so
bad nosym "-material_umat_symbol vumat_: not found in bin/umat_j2.so" $SMALL $UJ2 -material_umat_symbol vumat_
bad nan "did not converge" $SMALL -material_type umat -material_umat bin/umat_ctest.so -material_umat_symbol umat_nan_ -material_umat_props 69004,0.3 -load_max_cuts 2
# PNEWDT < 1: the material's MAT_ERR_CUTBACK fails the step at once and it is retried smaller
atrito 1 cut $SMALL -material_type umat -material_umat bin/umat_ctest.so -material_umat_symbol umat_cut_ -material_umat_props 69004,0.3 &&
  { d=$(grep -m1 '^done:' "$OUT/cut.log")
    if echo "$d" | grep -q ' [1-9][0-9]* cuts\?,' && grep -q 'the material asked for a smaller increment (a user material.s PNEWDT < 1; element id [0-9]*); retrying' "$OUT/cut.log"; then
      ok "PNEWDT 0.5 once: the step was cut, named, and the run finished ($d)"
    else not_ok "PNEWDT 0.5 once: no cut or no message ($d)"; grep -m3 'retrying\|error' "$OUT/cut.log" | indent; fi; }
