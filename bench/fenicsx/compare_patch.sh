#!/usr/bin/env bash
# fiberfold against FEniCSx on a patch in three dimensions, side by side on this machine, in
# one run:
#
#   bench/fenicsx/compare_patch.sh [ELEMENTS_PER_WAVELENGTH] [D_MAX]
#                                  (after cargo build --release and bench/fenicsx/install.sh)
#
# The case: Table 1 with beta = 0.7853982 (psi = 0) under equibiaxial compression, the patch one
# onset wavelength square with symmetry sides, ELEMENTS_PER_WAVELENGTH hexahedra along X and Z
# (default 4), the path to D_MAX (default 0.12). fiberfold runs `pattern --sides symmetry
# --follow-to D_MAX` (its first bifurcation by the inertia of the tangent, then the path with
# its adaptive steps of at most 0.005 and the inertia of every state: more work than the
# reference does); bench/fenicsx/patch.py then solves the same model on fiberfold's mesh (read
# from the run's state.vtu) with plain Newton and MUMPS on one core, at steps of 0.005. Prints
# both wall times, peak memory, their ratio, and the largest relative difference of A(d) over
# the d both reached: the check that both solved one problem.
set -euo pipefail
epw=${1:-4}
d_max=${2:-0.12}
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=bench/fenicsx/timing.sh
. "$here/timing.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

/usr/bin/time -f "%e %M" -o "$work/fiberfold.time" \
  "$binary" pattern --sides symmetry --set beta=0.7853982 --elements-per-wavelength "$epw" \
  --follow-to "$d_max" --out "$work/fiberfold" >"$work/fiberfold.log" 2>&1
unknowns=$(sed -n 's/.* \([0-9]*\) unknowns;.*/\1/p' "$work/fiberfold.log" | head -1)
reference=("$venv/bin/python" "$here/patch.py" --mesh-vtu "$work/fiberfold/state.vtu" --beta 0.7853982 --quiet)
time_reference "$d_max"
echo "patch with symmetry sides, $epw hexahedra per wavelength ($unknowns unknowns), displacement element, to d = $d_max"
print_times "$work/fiberfold/pattern.csv"
"$venv/bin/python" "$here/reference.py" compare "$work/fiberfold/pattern.csv" "$work/fenicsx.csv" "$ff_seconds" "$fx_seconds"
