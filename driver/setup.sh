#!/usr/bin/env bash
# One-time setup on Debian: FreeFEM with its plugins and includes, the fix for
# the Debian package's plugin/include paths, and the Python packages.
# Idempotent; quick when everything is already there.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"

as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

if ! command -v FreeFem++ >/dev/null || [ ! -e /usr/lib/freefem++/MUMPS_seq.so ] \
   || [ ! -e /usr/include/freefem++/idp/getARGV.idp ]; then
  echo "setup: installing FreeFEM from Debian packages"
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq freefem++ libfreefem++ libfreefem++-dev >/dev/null
fi

# Debian's /etc/freefem++.pref points at /usr/lib/ff++/4.9/{lib,idp}, which do
# not exist: add the real plugin and include folders once.
pref=/etc/freefem++.pref
if [ -w "$pref" ] || [ "$(id -u)" = 0 ]; then
  grep -q '/usr/lib/freefem++' "$pref" 2>/dev/null || echo 'loadpath += "/usr/lib/freefem++"' | as_root tee -a "$pref" >/dev/null
  grep -q '/usr/include/freefem++/idp' "$pref" 2>/dev/null || echo 'includepath += "/usr/include/freefem++/idp"' | as_root tee -a "$pref" >/dev/null
fi

py="${PYTHON:-python3}"
if ! "$py" -c "import numpy, pandas, matplotlib, tqdm, pytest, hypothesis" 2>/dev/null; then
  echo "setup: installing Python packages"
  # Debian's own Python refuses pip installs into the system (PEP 668)
  "$py" -m pip install -q -r "$root/requirements.txt" 2>/dev/null \
    || "$py" -m pip install -q --break-system-packages -r "$root/requirements.txt"
fi

# smoke test: the solver loads its plugins and runs a coarse case
(cd "$root/edp" && FreeFem++ -nw -v 0 hertz.edp -n 4 -L 50 >/dev/null) \
  || { echo "setup: FreeFEM smoke test failed" >&2; exit 1; }
echo "setup: ok ($(FreeFem++ -nw -v 0 2>&1 | grep -o 'version [0-9.]*' | head -1 || true))"
