#!/usr/bin/env bash
# fiberfold against FEniCSx on one wrinkling curve, side by side on this machine, in one run:
#
#   bench/fenicsx/compare.sh [coarse|fine] [D_MAX]      (after cargo build --release and
#                                                        bench/fenicsx/install.sh)
#
# The case: Table 1 with beta = 0.785398, 4.5 waves, imperfection 0.05, displacement element,
# no contact, to D_MAX (default 0.2). fiberfold runs `simulate` with its defaults otherwise (its
# adaptive steps of at most 0.005, its files); bench/fenicsx/wrinkle.py then solves the same
# model on fiberfold's mesh (read from the run's first snapshot) with plain Newton and MUMPS on
# one core, at steps of 0.005. Prints both wall times, peak memory, their ratio, and the largest
# relative difference of A(d) over the d both reached: the check that both solved one problem.
set -euo pipefail
mesh=${1:-coarse}
d_max=${2:-0.2}
case $mesh in coarse | fine) ;; *) echo "mesh: coarse or fine" >&2; exit 2 ;; esac
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=bench/fenicsx/timing.sh
. "$here/timing.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
case_flags=(--set beta=0.785398 --waves 4.5 --element displacement --no-contact)

/usr/bin/time -f "%e %M" -o "$work/fiberfold.time" \
  "$binary" simulate "${case_flags[@]}" --mesh "$mesh" --d-max "$d_max" --out "$work/fiberfold" \
  >"$work/fiberfold.log" 2>&1
reference=("$venv/bin/python" "$here/wrinkle.py" --mesh-vtu "$work/fiberfold/simulate_0000.vtu"
  --beta 0.785398 --quiet)
time_reference "$d_max"
echo "mesh $mesh, displacement element, to d = $d_max"
print_times "$work/fiberfold/amplitude.csv"
"$venv/bin/python" "$here/reference.py" compare "$work/fiberfold/amplitude.csv" "$work/fenicsx.csv" "$ff_seconds" "$fx_seconds"
