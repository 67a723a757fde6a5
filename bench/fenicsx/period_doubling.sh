#!/usr/bin/env bash
# The period doubling of a periodic wrinkle, found by fiberfold and checked by FEniCSx, in one run:
#
#   bench/fenicsx/period_doubling.sh [KEEP_DIR]     (after cargo build --release and
#                                                    bench/fenicsx/install.sh)
#
# The case: an isotropic bilayer of stiffness contrast 100 (mu_l = 100, K_l = 10^4, mu_s = 1,
# K_s = 100, phi_m = 1, phi_f = 0), the half domain 0 <= X <= 42.2142 two natural wavelengths
# long (nx = 40, the coarse preset's 2 + 25 elements through the layer and the depth of 50),
# seeded with 2 waves of imperfection -0.05 (a trough on each symmetry plane), the mixed element,
# no contact, to d = 0.25 at steps of at most 0.001 (the default 0.005 lets fiberfold's path
# jump near the onset, d ~ 0.026, to another branch). fiberfold `simulate` tracks the inertia of
# its tangent at every state and writes its changes to secondary.json; bench/fenicsx/wrinkle.py
# then solves the same model on fiberfold's mesh (read from the run's first snapshot, the
# imperfection included) with the same Q2/P1disc element (its pressures kept as unknowns, a
# saddle point) by plain Newton and MUMPS on one core, at steps of 0.001 from d = 0.005, and
# counts at every state the negative eigenvalues of its tangent on the free unknowns (MUMPS
# LDL^T of the saddle point, less one per pressure unknown; reference.py, `--inertia`).
# Prints both wall times, fiberfold's first change of the inertia (d before, d after, its mode's
# half waves across the domain), the reference's (last d with count 0, first d with a positive
# count, the count, its mode's half waves), their difference in d, the checks of the saddle
# point's inertia, at how many states the two counts agree (fiberfold's read off its log), and
# the largest relative difference of A(d) over the d both reached.
# FIBERFOLD names fiberfold's binary (default target/release/fiberfold); KEEP_DIR, when given,
# keeps both runs' files there.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=bench/fenicsx/timing.sh
. "$here/timing.sh"
if [ $# -ge 1 ]; then
  work=$1
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
step=0.001
d_max=0.25
rm -rf "$work/fiberfold"

/usr/bin/time -f "%e %M" -o "$work/fiberfold.time" \
  "$binary" simulate --set mu_l=100 --set K_l=10000 --set K_s=100 --set phi_m=1 --set phi_f=0 \
  --length 42.2142 --nx 40 --waves 2 --imperfection -0.05 --element mixed --no-contact \
  --max-step "$step" --d-max "$d_max" --out "$work/fiberfold" >"$work/fiberfold.log" 2>&1
reference=("$venv/bin/python" "$here/wrinkle.py" --mesh-vtu "$work/fiberfold/simulate_0000.vtu"
  --element mixed --inertia --mu_l 100 --K_l 10000 --mu_s 1 --K_s 100 --phi_m 1 --phi_f 0
  --d-first 0.005 --step "$step" --quiet)
time_reference "$d_max"
echo "period doubling: contrast 100, L = 42.2142 (2 wavelengths), nx = 40, mixed element, steps $step to d = $d_max"
print_times "$work/fiberfold/amplitude.csv" " (with the inertia of every state)"
"$venv/bin/python" "$here/reference.py" inertia "$work/fiberfold/secondary.json" \
  "$work/fiberfold/amplitude.csv" "$work/fenicsx.csv" "$work/fiberfold.log"
