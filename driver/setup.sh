#!/usr/bin/env bash
# One-time setup on Debian: FreeFEM with its plugins and includes, the fix for
# the Debian package's plugin/include paths, and this project as a Python
# package (pip install -e ".[test,lint]": the `hertz` command, the test
# tools, and Dask, so that the same setup makes a machine a sweep worker).
# With --peers, also the peer codes the benchmark compares against: FEniCS
# from Debian packages, Tamaas from PyPI into <checkout>/.venv-peers.
# Idempotent; quick when everything is already there.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"

as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }
apt_install() {
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$@" >/dev/null
}

if [ "${1:-}" = "--peers" ]; then
  if ! /usr/bin/python3 -c "import dolfin, gmsh" 2>/dev/null; then
    echo "setup: installing FEniCS 2019 and gmsh (python3-dolfin, python3-gmsh) for the peer benchmark"
    apt_install python3-dolfin python3-gmsh
  fi
  # Tamaas (FFT boundary elements, bench/tamaas_peer.py) comes from PyPI as a
  # wheel: into a virtual environment of its own, not into either system Python.
  # 2.9 or later: the version whose operators bench/tamaas_peer.py checked against Hertz.
  venv="$root/.venv-peers"
  if ! "$venv/bin/python" -c "import tamaas, numpy" 2>/dev/null; then
    echo "setup: installing Tamaas (pip install tamaas) into $venv for the peer benchmark"
    py="${PYTHON:-python3}"
    if [ ! -x "$venv/bin/python" ] && ! "$py" -m venv --clear "$venv" 2>/dev/null; then
      apt_install python3-venv  # Debian's python3 has no venv/ensurepip without it
      "$py" -m venv --clear "$venv"
    fi
    "$venv/bin/python" -m pip install -q --disable-pip-version-check "tamaas>=2.9" numpy
  fi
  exit 0
fi

if ! command -v FreeFem++ >/dev/null || [ ! -e /usr/lib/freefem++/MUMPS_seq.so ] \
   || [ ! -e /usr/include/freefem++/idp/getARGV.idp ] || ! dpkg -s libopenblas0-serial >/dev/null 2>&1; then
  echo "setup: installing FreeFEM from Debian packages"
  # the serial OpenBLAS replaces the reference BLAS under CHOLMOD and MUMPS
  # (update-alternatives): 3 to 5 times faster factorizations on 3D meshes,
  # one thread per case
  apt_install freefem++ libfreefem++ libfreefem++-dev libopenblas0-serial
fi
# the 3D solver is a FreeFEM plugin over CHOLMOD (edp/plugin): a C++ compiler and CHOLMOD's header
if ! command -v g++ >/dev/null || [ ! -e /usr/include/suitesparse/cholmod.h ]; then
  echo "setup: installing g++ and libsuitesparse-dev for the 3D solver plugin"
  apt_install g++ libsuitesparse-dev
fi

# Debian's /etc/freefem++.pref points at /usr/lib/ff++/4.9/{lib,idp}, which do
# not exist: add the real plugin and include folders once.
pref=/etc/freefem++.pref
if [ -w "$pref" ] || [ "$(id -u)" = 0 ]; then
  grep -q '/usr/lib/freefem++' "$pref" 2>/dev/null || echo 'loadpath += "/usr/lib/freefem++"' | as_root tee -a "$pref" >/dev/null
  grep -q '/usr/include/freefem++/idp' "$pref" 2>/dev/null || echo 'includepath += "/usr/include/freefem++/idp"' | as_root tee -a "$pref" >/dev/null
fi

py="${PYTHON:-python3}"
# the installed package must be this checkout's: asked from outside it, or a
# second clone would find its own driver/ on the path from its folder, skip
# the install, and keep `hertz` on the first clone's code
installed="$(cd / && "$py" -c "import os, driver, pytest, hypothesis, meshio, distributed, pyvista, scipy, ruff, mypy
print(os.path.realpath(os.path.dirname(driver.__file__)))" 2>/dev/null || true)"
if [ "$installed" != "$(realpath "$root/driver")" ] || ! command -v hertz >/dev/null; then
  echo "setup: installing the Python package and its test tools"
  # Debian's own Python refuses pip installs into the system (PEP 668)
  "$py" -m pip install -q -e "$root[test,lint]" 2>/dev/null \
    || "$py" -m pip install -q --break-system-packages -e "$root[test,lint]"
fi

sh "$root/edp/plugin/build.sh" || { echo "setup: the 3D solver plugin (edp/plugin) did not build" >&2; exit 1; }

# smoke test: the solver loads its plugins and runs a coarse case
rc=0
(cd "$root/edp" && FreeFem++ -nw -v 0 hertz.edp -n 8 >/dev/null) || rc=$?
[ $rc -eq 0 ] || { echo "setup: FreeFEM smoke test failed (exit $rc)" >&2; exit 1; }
echo "setup: ok ($(FreeFem++ -nw -v 0 2>&1 | grep -o 'version [0-9.]*' | head -1 || true))"
