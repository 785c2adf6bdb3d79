#!/bin/sh
# Builds the 3D branch's solver plugin (surfaceschur.so, beside its source)
# when it is missing or older than its source: run by make setup, and by a 3D
# run that finds it so (hertz.edp, lib/branch.idp). Needs g++, ff-c++
# (libfreefem++-dev) and CHOLMOD's header (libsuitesparse-dev). The plugin
# appears whole or not at all: sweeps start many runs at once.
set -e
cd "$(dirname "$0")"
[ surfaceschur.so -nt surfaceschur.cpp ] && exit 0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp surfaceschur.cpp "$tmp/"
if ! (cd "$tmp" && ff-c++ surfaceschur.cpp -lcholmod -llapack -lblas > build.log 2>&1); then
  grep -E "error" "$tmp/build.log" >&2 || cat "$tmp/build.log" >&2
  exit 1
fi
mv -f "$tmp/surfaceschur.so" surfaceschur.so
