#!/usr/bin/env bash
# The command line as a user meets it: -help lists every module's options and runs nothing, a bare
# call prints a usage line and fails, a misspelt option stops the run before any work with the
# closest known option, nothing is written into the options database behind the user's back, and
# the result files say what they mean (history.csv reactions on constrained components only,
# contact.csv displacement, path length and force vectors; an unwritable history fails on every
# rank); the generated options reference equals what the code registers.
cd "$(dirname "$0")/.." && . tests/lib.sh
OUT=$(test_out options)

# 1. -help: the options of every module, grouped, and nothing run
$MPI 1 $A -options_file cases/hemisphere_friction.opts -help -output_dir "$OUT/help" >"$OUT/help.log" 2>&1; rc=$?
miss=""
for o in -mesh_type -blank_radius -material_type -material_swift_n -element_type -fe_fbar -bc_clamp_set -bc_symx_components \
         -contact_friction -contact_penalty_normal -tool_names -tool_punch_ -tool_die_ -load_steps -newton_stall_its -output_dir \
         -checkpoint_interval -lu_ordering -assembly_coo -snes_rtol; do
  grep -q -- "$o" "$OUT/help.log" || miss="$miss $o"
done
groups=$(grep -cE '^(Mesh|Material|Element|Boundary condition|Contact|Tool|Load stepping|Results|Assembly)' "$OUT/help.log")
[ $rc -eq 0 ] && [ -z "$miss" ] && [ ! -e "$OUT/help" ] && [ "$groups" -ge 10 ] &&
  ok "-help lists the options of every module in $groups groups (per tool and per condition included), exits 0 and writes nothing" ||
  not_ok "-help: exit $rc, missing:$miss, $groups groups, output dir $( [ -e "$OUT/help" ] && echo written || echo absent)"

# 2. a bare call: one usage line, non-zero exit
(cd "$OUT" && "$OLDPWD/$A" >bare.out 2>bare.err); rc=$?
[ $rc -ne 0 ] && [ "$(wc -l <"$OUT/bare.err")" -eq 1 ] && grep -q '^atrito: error: .*usage: ' "$OUT/bare.err" && [ ! -e "$OUT/out" ] &&
  ok "a bare call prints one usage line and exits $rc, running nothing" ||
  { not_ok "bare call: exit $rc"; cat "$OUT/bare.err" | indent; }

# 3. misspelt options with the code's prefixes: stopped before any output, closest option named
spell() { # spell NP EXPECTED-SUGGESTION ARGS...
  local np=$1 want=$2; shift 2
  atrito_rc "$np" misspelt "$@"
  local line; line=$(grep -c 'atrito: error' "$OUT/misspelt.log")
  [ $RC -ne 0 ] && [ "$line" -eq 1 ] && grep -q "did you mean $want?" "$OUT/misspelt.log" && [ ! -e "$OUT/misspelt" ] &&
    ok "misspelt $* (np=$np): refused before the run, suggesting $want" ||
    { not_ok "misspelt $* (np=$np): exit $RC"; tail -n 3 "$OUT/misspelt.log" | indent; }
  rm -rf "$OUT/misspelt"
}
spell 1 -contact_friction -options_file cases/tension_bar.opts -contact_fricton 0.1
spell 2 -bc_pull_values -options_file cases/tension_bar.opts -bc_pul_values 2
spell 1 -material_hardening_modulus -options_file cases/tension_bar.opts -material_hardening_modulos 10
spell 1 -load_max_cuts -options_file cases/tension_bar.opts -load_max_cut 3
spell 2 -tool_punch_motion -options_file cases/hemisphere_friction_analytic.opts -tool_punch_moton 0,0,1

# an option far from every known name (one of a tool, patch type or condition this case does not
# have): warned before the run starts, not refused
atrito 1 farname -options_file cases/tension_bar.opts -load_steps 2 -output_interval 0 -contact_penalty 5 &&
  { w=$(grep -n 'WARNING: option -contact_penalty is read by no part of this case' "$OUT/farname.log" | head -1 | cut -d: -f1)
    s=$(grep -n '^step ' "$OUT/farname.log" | head -1 | cut -d: -f1)
    [ -n "$w" ] && [ -n "$s" ] && [ "$w" -lt "$s" ] && ok "an option no part of the case reads, far from every known name: warned before the first step, the run goes on" ||
      not_ok "-contact_penalty: warning line ${w:-none}, first step line ${s:-none}"; }

# 4. nothing written into the options database: the Gmsh reader's regions and MUMPS's scaling
atrito 1 gmshopts -mesh_file tests/data/two_hex.msh -bc_names fix,pull -bc_fix_set left -bc_pull_set right -bc_fix_components x,y,z -bc_pull_components x -bc_pull_values 0.2 -load_steps 2 -output_interval 0 -options_view &&
  { n=$(grep -cE 'dm_plex_gmsh_use_regions|mat_mumps_icntl_8' "$OUT/gmshopts.log")
    [ "$n" -eq 0 ] && ok "a Gmsh mesh with named regions and the MUMPS LU leave the options database as the user gave it" ||
      not_ok "options written behind the user's back: $(grep -E 'dm_plex_gmsh_use_regions|mat_mumps_icntl_8' "$OUT/gmshopts.log" | tr '\n' ' ')"; }

# 5. history.csv: a reaction per constrained component only; contact.csv: vectors and path length
for np in 1 2; do
  atrito $np drag$np -options_file cases/block_plane_drag.opts -output_interval 0 &&
    pycheck contact_columns "$OUT/drag$np" "hold_fx,hold_fy,hold_fz,plane_fy" "0,0,0,0;0.5,0,0,0.01;1,0.05,0,0.01" 0.3 "np=$np"
done
atrito 1 sphere0 -options_file cases/block_sphere.opts -contact_friction 0 -output_interval 0 -load_steps 10 &&
  pycheck contact_columns "$OUT/sphere0" "base_fx,base_fy,base_fz" "0,0,0,0;0.5,0,0,-0.1;1,0.2,0,-0.1" 0 "frictionless sphere"

# 6. the history file cannot be written: one line, every rank stops (no rank left in a collective)
mkdir -p "$OUT/nohist/history.csv"
timeout 120 $MPI 2 $A -options_file cases/tension_bar.opts -load_steps 2 -output_dir "$OUT/nohist" >"$OUT/nohist.log" 2>&1; rc=$?
alone 2 "$OUT/nohist" -options_file cases/tension_bar.opts -load_steps 2; arc=$?
[ $rc -ne 0 ] && [ $rc -ne 124 ] && [ $arc -ne 124 ] && [ "$(grep -c 'atrito: error' "$OUT/nohist.log")" -eq 1 ] && grep -q "cannot write '$OUT/nohist/history.csv' (-output_dir)" "$OUT/nohist.log" &&
  ok "an unwritable history.csv on 2 ranks: one error line, every rank exits ($rc), by itself (no rank waits when mpiexec does not end the job)" ||
  { not_ok "unwritable history.csv: exit $rc, without mpiexec's kill $arc (124: a rank left waiting)"; tail -n 4 "$OUT/nohist.log" | indent; }

# 7. the options reference (doc/reference/options.md, scripts/options_reference.py) is what the
#    code registers, every option with a description; a page that differs (an option renamed in
#    the code, or a line edited by hand) fails the check
out=$($PY scripts/options_reference.py --check 2>&1); rc=$?
[ $rc -eq 0 ] && ok "doc/reference/options.md equals what -help lists ($out), every option described" ||
  { not_ok "doc/reference/options.md differs from the code's options or an option has no description (exit $rc)"; echo "$out" | head -n 12 | indent; }
sed 's/^- `-load_steps` (default `10`)/- `-load_steps` (default `12`)/' doc/reference/options.md >"$OUT/options_tampered.md"
out=$($PY scripts/options_reference.py --check --file "$OUT/options_tampered.md" 2>&1); rc=$?
[ $rc -ne 0 ] && grep -q -- '-load_steps' <<<"$out" &&
  ok "a reference whose -load_steps default differs from the code's fails the check, naming the line" ||
  { not_ok "a tampered reference passed the check (exit $rc)"; echo "$out" | head -n 5 | indent; }
