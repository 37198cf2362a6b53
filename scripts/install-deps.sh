#!/usr/bin/env bash
# Installs the Debian packages the code needs, only those that are missing.
set -euo pipefail
need=()
pkg-config --exists PETSc 2>/dev/null || need+=(petsc-dev)
[ -f /usr/include/metis.h ] || need+=(libmetis-dev)
[ -f /usr/include/dmumps_c.h ] || need+=(libmumps-dev)
[ -f /usr/include/hdf5/openmpi/hdf5.h ] || need+=(libhdf5-openmpi-dev)
command -v mpiexec >/dev/null 2>&1 || need+=(openmpi-bin)
command -v mpicc >/dev/null 2>&1 || need+=(libopenmpi-dev)
# an optimised BLAS: MUMPS factorisations are about 10x faster than with the reference BLAS
ls /usr/lib/x86_64-linux-gnu/openblas-pthread/libblas.so.3 >/dev/null 2>&1 || need+=(libopenblas0-pthread)
/usr/bin/python3 -c "import numpy" >/dev/null 2>&1 || need+=(python3-numpy)
/usr/bin/python3 -c "import h5py" >/dev/null 2>&1 || need+=(python3-h5py)
/usr/bin/python3 -c "import matplotlib" >/dev/null 2>&1 || need+=(python3-matplotlib)
if [ ${#need[@]} -gt 0 ]; then
  echo "install-deps: installing ${need[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" make gcc >/dev/null
fi
