#!/usr/bin/env bash
# Installs what cfe2d needs to build, run and test, and only what is
# missing: gfortran, LAPACK/BLAS, SuiteSparse, METIS, gmsh, and MUMPS with
# Open MPI (the MUMPS backend, mpirun) from Debian,
# numpy, matplotlib and meshio from PyPI; CalculiX's test decks (Debian's
# calculix-ccx-test, data only). Safe to run again: it says what it finds.
set -euo pipefail

PYTHON=${PYTHON:-python3}
apt_pkgs=(gfortran liblapack-dev libopenblas-dev libarpack2-dev libsuitesparse-dev libmetis-dev gmsh libmumps-dev openmpi-bin libopenmpi-dev)
missing=()
for p in "${apt_pkgs[@]}"; do
  if dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    :
  else
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing from Debian: ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
      echo "install-deps: not root and no sudo: install ${missing[*]} by hand" >&2; exit 1
    fi
  fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
else
  echo "install-deps: Debian packages present (${apt_pkgs[*]})"
fi

# CalculiX's test decks, data only (tests/test_calculix_suite_debian.py and
# test_nonlinear_calculix.py compare with their reference results); not the
# solver the package recommends: the tests never run CalculiX.
if ! dpkg-query -W -f='${Status}' calculix-ccx-test 2>/dev/null | grep -q "install ok installed"; then
  echo "install-deps: installing CalculiX's test decks (calculix-ccx-test)"
  SUDO=""
  if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then SUDO="sudo"; fi
  if ! { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
         --no-install-recommends calculix-ccx-test >/dev/null; }; then
    echo "install-deps: calculix-ccx-test not installed: the tests of CalculiX's decks are skipped" >&2
  fi
fi

py_missing=()
for mod in numpy matplotlib meshio; do
  "$PYTHON" -c "import $mod" 2>/dev/null || py_missing+=("$mod")
done
if [ ${#py_missing[@]} -gt 0 ]; then
  echo "install-deps: installing Python packages: ${py_missing[*]}"
  "$PYTHON" -m pip install --quiet --disable-pip-version-check "${py_missing[@]}"
else
  echo "install-deps: Python packages present (numpy matplotlib meshio)"
fi

# The clients of CalculiX's result files the tests run on cfe2d's .frd
# (tests/test_frd.py; skipped with a message where missing): cgx from
# Debian, ccx2paraview and the vtk module it needs and pycalculix from
# PyPI. A failure here is not fatal: the tests say what is missing.
if ! command -v cgx >/dev/null 2>&1; then
  echo "install-deps: installing cgx (calculix-cgx)"
  SUDO=""
  if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then SUDO="sudo"; fi
  if ! { $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
         --no-install-recommends calculix-cgx >/dev/null; }; then
    echo "install-deps: calculix-cgx not installed: the cgx test of the .frd is skipped" >&2
  fi
fi
if ! "$PYTHON" -c "import ccx2paraview, vtk" 2>/dev/null; then
  echo "install-deps: installing ccx2paraview and vtk from PyPI"
  "$PYTHON" -m pip install --quiet --disable-pip-version-check ccx2paraview vtk || \
    echo "install-deps: ccx2paraview not installed: its test of the .frd is skipped" >&2
fi
if ! "$PYTHON" -c "import importlib.util, sys; sys.exit(importlib.util.find_spec('pycalculix') is None)" 2>/dev/null; then
  echo "install-deps: installing pycalculix from PyPI"
  "$PYTHON" -m pip install --quiet --disable-pip-version-check pycalculix || \
    echo "install-deps: pycalculix not installed: its test of the .frd and .dat is skipped" >&2
fi
