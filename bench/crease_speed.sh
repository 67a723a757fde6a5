#!/usr/bin/env bash
# The crease onset and a small map, timed back to back with two fiberfold binaries on this
# machine, with their answers side by side.
#
#   bench/crease_speed.sh OLD NEW OUT [CASE ...]
#
#   OLD, NEW  two fiberfold binaries
#   OUT       output folder: OUT/<binary>/<case>/ (each run's files and log), and
#             OUT/crease_speed.md (the table printed)
#   CASE      the cases to run (default: all three, in the order below)
#
# Cases, each run by OLD then NEW:
#   contrast5  crease of an isotropic bilayer, mu_l / mu_s = 5, K = 100 mu (the wrinkle first)
#   contrast3  the same at mu_l / mu_s = 3 (the crease first, near the crossover)
#   map2x2     map of mu_l in [3, 10] against beta in [0, pi/2], 2 x 2 points, Table 1 otherwise
# Columns: the wall time of each (s), NEW / OLD, and the answers: d_crease (with its
# uncertainty) and first for a crease, first / becomes per point for the map.
set -euo pipefail

if [[ $# -lt 3 ]]; then
  echo "usage: $0 OLD NEW OUT [CASE ...]" >&2
  exit 2
fi
OLD=$(realpath "$1")
NEW=$(realpath "$2")
OUT=$3
shift 3
CASES=("${@:-contrast5 contrast3 map2x2}")
# shellcheck disable=SC2206
CASES=(${CASES[*]})
mkdir -p "$OUT"

ISOTROPIC=(--set K_s=100 --set phi_m=1 --set phi_f=0)
declare -A ARGS=(
  [contrast5]="crease --set mu_l=5 --set K_l=500 ${ISOTROPIC[*]}"
  [contrast3]="crease --set mu_l=3 --set K_l=300 ${ISOTROPIC[*]}"
  [map2x2]="map --x mu_l --x-from 3 --x-to 10 --x-points 2 --y beta --y-from 0 --y-to 1.5708 --y-points 2"
)

# Runs one case with one binary; prints its wall time in seconds.
run() {
  local binary=$1 which=$2 case=$3
  local dir="$OUT/$which/$case"
  rm -rf "$dir"
  mkdir -p "$dir"
  local start end
  start=$(date +%s.%N)
  # shellcheck disable=SC2086
  "$binary" ${ARGS[$case]} --out "$dir" >"$dir.log" 2>&1
  end=$(date +%s.%N)
  python3 -c "print(f'{$end - $start:.1f}')"
}

# The answers a case's files give.
answers() {
  local dir=$1 case=$2
  python3 - "$dir" "$case" <<'EOF'
import json, sys
folder, case = sys.argv[1], sys.argv[2]
if case == "map2x2":
    points = json.load(open(f"{folder}/map.json"))["points"]
    print("; ".join(f"({p['x']:g}, {p['y']:.4g}): {p['first']} / {p['becomes'] or '-'}" for p in points))
else:
    r = json.load(open(f"{folder}/crease.json"))
    d, e = r.get("d_crease"), r.get("d_crease_error")
    crease = "none" if d is None else f"{d:.5f} +- {e:.1e}"
    print(f"d_crease {crease}, first {r.get('first', '(not reported)')}")
EOF
}

{
  echo "| case | old (s) | new (s) | new / old | old's answer | new's answer |"
  echo "|---|---:|---:|---:|---|---|"
} >"$OUT/crease_speed.md"
for case in "${CASES[@]}"; do
  if [[ -z "${ARGS[$case]:-}" ]]; then
    echo "unknown case '$case' (contrast5, contrast3 or map2x2)" >&2
    exit 2
  fi
  echo "$case: old..." >&2
  old_seconds=$(run "$OLD" old "$case")
  echo "$case: new..." >&2
  new_seconds=$(run "$NEW" new "$case")
  ratio=$(python3 -c "print(f'{$new_seconds / $old_seconds:.3f}')")
  echo "| $case | $old_seconds | $new_seconds | $ratio | $(answers "$OUT/old/$case" "$case") | $(answers "$OUT/new/$case" "$case") |" \
    >>"$OUT/crease_speed.md"
done
echo "old: $OLD; new: $NEW; one run each, in turn, on $(nproc) cores" >>"$OUT/crease_speed.md"
cat "$OUT/crease_speed.md"
