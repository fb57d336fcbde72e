#!/usr/bin/env bash
# Installs what cfe2d needs to build, run and test, and only what is
# missing: gfortran, LAPACK/BLAS, SuiteSparse, METIS and gmsh from Debian,
# numpy, matplotlib and meshio from PyPI; CalculiX's test decks
# (calculix-ccx-test: data only, read by tests/test_nonlinear_calculix.py). Safe to run again: it says what it finds.
set -euo pipefail

PYTHON=${PYTHON:-python3}
apt_pkgs=(gfortran liblapack-dev libopenblas-dev libsuitesparse-dev libmetis-dev gmsh calculix-ccx-test)
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
