#!/bin/sh
# Builds the 3D branch's solver plugin (surfaceschur.so) when it is missing or
# older than its source: run by make setup, and by a 3D run that finds it so
# (hertz.edp, lib/branch.idp). Needs g++, ff-c++ (libfreefem++-dev) and
# CHOLMOD's header (libsuitesparse-dev). The plugin appears whole or not at
# all: sweeps start many runs at once.
# It goes beside its source in a checkout. Where that folder takes no file (an
# installed package in a read-only site-packages, a shared image), it goes to
# the user's cache, keyed by the source and FreeFEM: never into the package.
#   build.sh            build if needed (exit 1, the compiler's lines on stderr, if it cannot)
#   build.sh --folder   print the folder that holds plugin/surfaceschur.so (FreeFEM's load path)
set -e
here=$(cd "$(dirname "$0")" && pwd)
if probe=$(mktemp "$here/.write-probe.XXXXXX" 2>/dev/null); then
  rm -f "$probe"
  home=$(dirname "$here")
else
  key=$(cat "$here/surfaceschur.cpp" "$(command -v FreeFem++)" | sha256sum | cut -c1-16)
  home="${XDG_CACHE_HOME:-${HOME:-/tmp}/.cache}/hertz-contact/plugin-$key"
fi
if [ "$1" = "--folder" ]; then echo "$home"; exit 0; fi
mkdir -p "$home/plugin"
cd "$home/plugin"
[ surfaceschur.so -nt "$here/surfaceschur.cpp" ] && exit 0
tmp=$(mktemp -d "$home/plugin/.build.XXXXXX")  # beside its place: the rename is atomic
trap 'rm -rf "$tmp"' EXIT
cp "$here/surfaceschur.cpp" "$tmp/"
if ! (cd "$tmp" && ff-c++ surfaceschur.cpp -lcholmod -llapack -lblas > build.log 2>&1); then
  grep -E "error" "$tmp/build.log" >&2 || cat "$tmp/build.log" >&2
  exit 1
fi
mv -f "$tmp/surfaceschur.so" surfaceschur.so
