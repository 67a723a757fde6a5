#!/usr/bin/env bash
# Installs FEniCSx (DOLFINx 0.11 with PETSc and MUMPS, the `dolfinx-solver-real` wheel from PyPI)
# for bench/fenicsx/compare.sh, into $FENICSX_DIR (default ~/.cache/fiberfold-fenicsx-bench).
#
# The wheel needs CPython 3.12 or newer. Where the system's Python is older (Debian bookworm has
# 3.11), CPython 3.13 is compiled from the source package of Debian trixie, fetched through apt
# with a sources list of its own (the system's apt configuration is left as it is). Needs
# root for apt, a C compiler, and about 5 minutes on 2 cores; run it once.
set -euo pipefail
prefix=${FENICSX_DIR:-$HOME/.cache/fiberfold-fenicsx-bench}
mkdir -p "$prefix"
cd "$prefix"

python=""
for candidate in python3.13 python3.12 python3; do
  if command -v "$candidate" >/dev/null &&
    "$candidate" -c 'import sys; sys.exit(sys.version_info < (3, 12))' 2>/dev/null; then
    python=$(command -v "$candidate")
    break
  fi
done

if [ -z "$python" ] && [ ! -x cpython/bin/python3 ]; then
  echo "building CPython 3.13 from Debian trixie's sources (once)"
  apt_dir=$(mktemp -d)
  trap 'rm -rf "$apt_dir"' EXIT
  mirror=$(sed -n 's/^URIs: *//p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -1)
  echo "deb-src ${mirror:-http://deb.debian.org/debian} trixie main" >"$apt_dir/sources.list"
  mkdir -p "$apt_dir/parts" "$apt_dir/state/partial" "$apt_dir/cache/archives/partial"
  own_apt=(-o "Dir::Etc::SourceList=$apt_dir/sources.list" -o "Dir::Etc::SourceParts=$apt_dir/parts"
    -o "Dir::State::Lists=$apt_dir/state" -o "Dir::Cache=$apt_dir/cache")
  apt-get "${own_apt[@]}" update -qq
  (cd "$apt_dir" && apt-get "${own_apt[@]}" source --download-only python3.13 >/dev/null)
  rm -rf source && mkdir source
  tar -xf "$apt_dir"/python3.13_*.orig.tar.xz -C source --strip-components=1
  (cd source && ./configure --prefix="$prefix/cpython" --with-ensurepip=install >configure.log 2>&1 &&
    make -j"$(nproc)" >make.log 2>&1 && make install >install.log 2>&1)
  rm -rf source
fi
[ -n "$python" ] || python=$prefix/cpython/bin/python3

[ -x venv/bin/python ] || "$python" -m venv venv
venv/bin/pip install --quiet --upgrade pip
venv/bin/pip install --quiet dolfinx-solver-real==0.11.0.post0
venv/bin/python -c "import dolfinx_solver, dolfinx; from petsc4py import PETSc; print('FEniCSx', dolfinx.__version__, 'with PETSc', PETSc.Sys.getVersion(), 'in', '$prefix/venv')"
