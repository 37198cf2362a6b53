#!/usr/bin/env bash
# The first `make all`, `make check` and `make run` on a machine without PETSc, the way a new user
# meets them: the Makefile is copied into an empty directory with stub sources, and PATH starts
# with fakes of the tools it calls. The fake pkg-config knows PETSc (-I/fake/petsc/include) only
# once the fake installer (standing in for scripts/install-deps.sh) has run, as on a bare Debian
# machine; the fake mpicc records its command lines. The first compile and link lines must carry
# PETSc's flags: a Makefile that asks pkg-config when it is read (`:=`) fails this test.
# Then scripts/install-deps.sh itself on a machine where nothing is installed (fake apt-get, sudo, id).
#
# usage: tests/test_build.sh [MAKEFILE]   (default: the repository's Makefile)
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
MK=$(realpath "${1:-Makefile}")
OUT=$(realpath "$(test_out build)")

# a make started from make check must not inherit the outer make's flags and overrides
MAKE_CLEAN="env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u MAKEOVERRIDES -u INSTALL_DEPS -u CC -u PYTHON"

sandbox() { # sandbox DIR: a project tree with stub sources and fake tools in DIR/fake
  local d=$1
  mkdir -p "$d"/{src/mod,include,tests,scripts,fake}
  cp "$MK" "$d/Makefile"
  echo 'int main(void) { return 0; }' >"$d/src/main.c"
  echo 'int f(void) { return 1; }' >"$d/src/mod/f.c"
  echo 'int g(void) { return 2; }' >"$d/src/g.c"
  echo '#define X 1' >"$d/include/x.h"
  echo '#define Y 1' >"$d/tests/testutil.h"
  echo 'int main(void) { return 0; }' >"$d/tests/test_stub.c"
  printf '#!/bin/sh\necho "ok - stub suite (PYTHON=$PYTHON)"; echo "1 passed, 0 failed"\n' >"$d/tests/run_tests.sh"
  printf '#!/bin/sh\necho "stub main job"\n' >"$d/scripts/run-main.sh"
  # the installer: afterwards PETSc is "installed"
  printf '#!/bin/sh\necho install >>"%s/fake/calls"; touch "%s/fake/petsc-installed"\n' "$d" "$d" >"$d/scripts/install-deps.sh"
  cat >"$d/fake/pkg-config" <<EOF
#!/bin/sh
echo "pkg-config \$*" >>"$d/fake/calls"
[ -e "$d/fake/petsc-installed" ] || exit 1
case "\$*" in
  *--cflags*PETSc*) echo "-I/fake/petsc/include" ;;
  *--libs*PETSc*) echo "-L/fake/petsc/lib -lpetsc_fake" ;;
  *--exists*PETSc*) exit 0 ;;
  *) exit 1 ;;
esac
EOF
  cat >"$d/fake/mpicc" <<EOF
#!/bin/sh
echo "mpicc \$*" >>"$d/fake/calls"
out=
while [ \$# -gt 0 ]; do [ "\$1" = -o ] && out=\$2; shift; done
[ -n "\$out" ] && : >"\$out"
EOF
  cat >"$d/fake/gcc-ar" <<EOF
#!/bin/sh
echo "gcc-ar \$*" >>"$d/fake/calls"
: >"\$2"
EOF
  chmod +x "$d"/fake/* "$d"/scripts/*.sh "$d"/tests/*.sh
}

for target in all check run; do
  d="$OUT/$target"
  rm -rf "$d"; sandbox "$d"
  (cd "$d" && PATH="$d/fake:$PATH" $MAKE_CLEAN make "$target" >"$d/make.log" 2>&1); rc=$?
  first_cc=$(grep -m1 '^mpicc .* -c ' "$d/fake/calls")
  first_link=$(grep -m1 '^mpicc .*-o bin/atrito' "$d/fake/calls")
  inst=$(grep -n -m1 '^install' "$d/fake/calls" | cut -d: -f1)
  cc_line=$(grep -n -m1 '^mpicc ' "$d/fake/calls" | cut -d: -f1)
  if [ "$rc" -eq 0 ] && [ -n "$inst" ] && [ -n "$cc_line" ] && [ "$inst" -lt "$cc_line" ] &&
     [[ "$first_cc" == *"-I/fake/petsc/include"* ]] && [[ "$first_link" == *"-lpetsc_fake"* ]]; then
    ok "first 'make $target' without PETSc: installer first, then the first compile carries -I/fake/petsc/include and the link -lpetsc_fake"
  else
    not_ok "first 'make $target' without PETSc (exit $rc): first compile line '${first_cc:-none}', link '${first_link:-none}'"
    tail -n 5 "$d/make.log" | indent
  fi
  case $target in
    check) grep -q '^1 passed, 0 failed' "$d/make.log" && ok "first 'make check' ran the suite: $(grep -o 'PYTHON=[^)]*' "$d/make.log")" || not_ok "first 'make check' did not run the suite" ;;
    run) grep -q 'stub main job' "$d/make.log" && ok "first 'make run' ran the main job" || not_ok "first 'make run' did not run the main job" ;;
  esac
done

# a second 'make all' finds everything built and does nothing, and does not install again
d="$OUT/all"
(cd "$d" && PATH="$d/fake:$PATH" $MAKE_CLEAN make all >"$d/make2.log" 2>&1); rc=$?
n=$(grep -c '^install' "$d/fake/calls")
[ "$rc" -eq 0 ] && [ "$n" -eq 1 ] && grep -q 'Nothing to be done' "$d/make2.log" &&
  ok "second 'make all': nothing to rebuild, installer not run again" || not_ok "second 'make all' (exit $rc, installer run $n times)"

# scripts/install-deps.sh on a machine where nothing is installed, as a user who is not root: the
# package lists are read first, sudo carries DEBIAN_FRONTEND, the compilers and tools are asked for
d="$OUT/install"; rm -rf "$d"; mkdir -p "$d/bin"
for t in bash sh env cat ls grep; do ln -s "$(command -v $t)" "$d/bin/$t"; done
printf '#!/bin/sh\necho 1000\n' >"$d/bin/id"
printf '#!/bin/sh\necho "sudo $*" >>"%s/calls"\nexec "$@"\n' "$d" >"$d/bin/sudo"
printf '#!/bin/sh\necho "apt-get DEBIAN_FRONTEND=${DEBIAN_FRONTEND:-} $*" >>"%s/calls"\n' "$d" >"$d/bin/apt-get"
chmod +x "$d"/bin/*
PATH="$d/bin" INSTALL_DEPS_PYTHON="$d/none/python3" INSTALL_DEPS_ROOT="$d/none" bash scripts/install-deps.sh >"$d/log" 2>&1; rc=$?
upd=$(grep -n -m1 'apt-get .*update' "$d/calls" 2>/dev/null | cut -d: -f1)
ins=$(grep -m1 'apt-get .*install' "$d/calls" 2>/dev/null)
insn=$(grep -n -m1 'apt-get .*install' "$d/calls" 2>/dev/null | cut -d: -f1)
miss=""
for p in make gcc pkg-config python3 petsc-dev libmumps-dev libmetis-dev libhdf5-openmpi-dev openmpi-bin libopenmpi-dev python3-markdown; do
  [[ " $ins " == *" $p "* ]] || miss="$miss $p"
done
# (it ends with an error: the fake apt-get installs nothing, and the script checks the result)
[ -n "$upd" ] && [ -n "$insn" ] && [ "$upd" -lt "$insn" ] && [ -z "$miss" ] && [[ "$ins" == *"DEBIAN_FRONTEND=noninteractive"* ]] &&
  grep -q '^sudo ' "$d/calls" && [ "$rc" -ne 0 ] && grep -q 'install-deps: ' "$d/log" &&
  ok "install-deps.sh on a bare machine (not root): apt-get update, then install through sudo, noninteractive, with make, gcc, pkg-config, python3" ||
  { not_ok "install-deps.sh on a bare machine (exit $rc): missing '$miss'"; cat "$d/calls" "$d/log" 2>/dev/null | indent; }
# without sudo, as a user who is not root: a clear message, no attempt
rm -f "$d/bin/sudo" "$d/calls"
PATH="$d/bin" INSTALL_DEPS_PYTHON="$d/none/python3" INSTALL_DEPS_ROOT="$d/none" bash scripts/install-deps.sh >"$d/log2" 2>&1; rc=$?
[ "$rc" -ne 0 ] && [ ! -e "$d/calls" ] && grep -q 'install-deps: .*root.*sudo' "$d/log2" &&
  ok "install-deps.sh without root and without sudo: $(grep -m1 "install-deps: error" "$d/log2" | cut -c1-110)" ||
  { not_ok "install-deps.sh without root and sudo (exit $rc)"; cat "$d/log2" | indent; }
