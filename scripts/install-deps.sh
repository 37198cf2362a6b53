#!/usr/bin/env bash
# Installs the Debian packages the code needs, only those that are missing. Works on a bare
# Debian 12 machine: the package lists are read first (a fresh image has none), the compilers,
# pkg-config and python3 are installed with the libraries, sudo is used only when not root (and
# is not needed then), and what was asked for is checked afterwards.
# (INSTALL_DEPS_ROOT and INSTALL_DEPS_PYTHON move the file checks, for tests/test_build.sh.)
set -euo pipefail
R=${INSTALL_DEPS_ROOT:-}
PY=${INSTALL_DEPS_PYTHON:-/usr/bin/python3}
have() { command -v "$1" >/dev/null 2>&1; }
need=()
have make || need+=(make)
have gcc && have gcc-ar || need+=(gcc)
have pkg-config || need+=(pkg-config)
[ -x "$PY" ] || need+=(python3)
{ have pkg-config && pkg-config --exists PETSc 2>/dev/null; } || need+=(petsc-dev)
[ -f "$R/usr/include/metis.h" ] || need+=(libmetis-dev)
[ -f "$R/usr/include/dmumps_c.h" ] || need+=(libmumps-dev)
[ -f "$R/usr/include/hdf5/openmpi/hdf5.h" ] || need+=(libhdf5-openmpi-dev)
# hypre's headers and library: BoomerAMG for the displacement system (src/solver/amg.c)
[ -f "$R/usr/include/hypre/HYPRE_parcsr_ls.h" ] || need+=(libhypre-dev)
have mpiexec || need+=(openmpi-bin)
have mpicc || need+=(libopenmpi-dev)
# the Fortran user materials of the tests (tests/umat_*.f)
have gfortran || need+=(gfortran)
# valgrind's memcheck (tests/test_valgrind.sh, `make memcheck`)
have valgrind || need+=(valgrind)
# an optimised BLAS: MUMPS factorisations are about 10x faster than with the reference BLAS
[ -e "$R/usr/lib/x86_64-linux-gnu/openblas-pthread/libblas.so.3" ] || need+=(libopenblas0-pthread)
"$PY" -c "import numpy" >/dev/null 2>&1 || need+=(python3-numpy)
"$PY" -c "import h5py" >/dev/null 2>&1 || need+=(python3-h5py)
"$PY" -c "import matplotlib" >/dev/null 2>&1 || need+=(python3-matplotlib)
# the guide's HTML (`make doc`, scripts/make_doc.py)
"$PY" -c "import markdown" >/dev/null 2>&1 || need+=(python3-markdown)
[ ${#need[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${need[*]}"
SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  if ! have sudo; then
    echo "install-deps: error: not root and no sudo; install these packages as root: apt-get install ${need[*]}" >&2
    exit 1
  fi
  SUDO=(sudo)
fi
# sudo resets the environment: DEBIAN_FRONTEND goes through env
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null

missing=()
have mpicc || missing+=(mpicc)
have pkg-config && pkg-config --exists PETSc 2>/dev/null || missing+=("PETSc (pkg-config)")
"$PY" -c "import h5py, numpy" >/dev/null 2>&1 || missing+=("python3 with h5py and numpy")
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: error: still missing after apt-get install: ${missing[*]}" >&2
  exit 1
fi
