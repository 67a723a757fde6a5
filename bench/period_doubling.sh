#!/usr/bin/env bash
# Writes the table and picture of the guide's page "What the wrinkle becomes at high contrast"
# (docs/guide/src/results/period-doubling-table.md, figures/period-doubling.png: the contrast-100
# bilayer's seeded path at d = 0.24) from `fiberfold simulate` runs of isotropic
# bilayers (phi_m = 1, phi_f = 0) at stiffness contrasts mu_l / mu_s of 5, 10, 30, 100 and 1000,
# each with K / mu = 3 (Table 1's Poisson ratio), K / mu = 100, and exactly incompressible; then
# Table 1's tissue with its fibres at beta = 0, pi/4 and pi/2.
#
# Each case runs on a half domain two natural wavelengths long (2 pi / k0 of `fiberfold onset`),
# seeded with a trough on each symmetry plane (--imperfection -0.05), so that the doubled period
# of the troughs fits it; the substrate is at least as deep as the domain is long. Steps are at
# most 0.001 in d, so that the path stays on the stable branch past the onset. Two runs a case:
#   1. the periodic wrinkle: its secondary bifurcation (the first change of the tangent's
#      inertia) and that mode's half waves across the domain (2: the period doubles); where the
#      count later returns to zero, the path has left the unstable periodic branch (listed apart);
#   2. the same seeded with 0.01 of that mode: what the path becomes (the troughs at its end).
# On two meshes: 20 elements a wavelength with 2 through the layer, and 40 with 4.
#
#   bench/period_doubling.sh        (after cargo build --release; about an hour on 2 cores, most
#                                    of it the contrasts 5 and 10 followed through contact)
#   bench/period_doubling.sh table  (the table of the runs done so far, running none)
#   bench/period_doubling.sh long   (contrasts 5 and 10 at K / mu = 3 and 100 on a half domain
#                                    eight natural wavelengths long, the coarse mesh: whether the
#                                    wrinkle's first secondary mode is the doubled period or a
#                                    long-wave modulation, the start of a fold; its own table,
#                                    period-doubling-long-table.md; about half an hour)
#
# Runs are kept in $PD_WORK (default results/period-doubling-study): a run whose secondary.json is
# there is not run again.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
binary=${FIBERFOLD:-$root/target/release/fiberfold}
work=${PD_WORK:-$root/results/period-doubling-study}
[ -x "$binary" ] || { echo "no $binary: run cargo build --release first (or set FIBERFOLD)" >&2; exit 1; }
mkdir -p "$work"
mode=${1:-all}
# Natural wavelengths across the half domain, and how far past the onset the path goes.
if [ "$mode" = long ]; then
  WAVELENGTHS=8 PAST_ONSET=0.15 table=$root/docs/guide/src/results/period-doubling-long-table.md
else
  WAVELENGTHS=2 PAST_ONSET=0.3 table=$root/docs/guide/src/results/period-doubling-table.md
fi

# The stiff layers first: the literature's period doubling is theirs.
CONTRASTS=(100 1000 30 10 5)
# name, then the bulk moduli's parameters given mu_l = $ratio
compressibility() {
  case $1 in
    K3) echo "--set K_l=$(python3 -c "print(3 * $2)") --set K_s=3" ;;
    K100) echo "--set K_l=$(python3 -c "print(100 * $2)") --set K_s=100" ;;
    incompressible) echo "--set incompressible=true" ;;
  esac
}
# mesh name, elements per wavelength, layer elements, substrate elements, h0
MESHES=("coarse 20 2 25 0.5" "fine 40 4 45 0.25")
[ "$mode" != long ] || MESHES=("${MESHES[0]}")

json() { python3 -c "import json, sys; print(json.load(open(sys.argv[1]))$2)" "$1"; }

# One run (unless done): out folder, then simulate's flags. A run that stops early keeps its path.
run() {
  local out=$1
  shift
  if [ -f "$out/secondary.json" ] || [ "$mode" = table ]; then return 0; fi
  timeout 900 "$binary" simulate "$@" --out "$out" >"$out.log" 2>&1 || {
    [ $? -ne 124 ] || echo "error: stopped at the study's limit of 900 s" >>"$out.log"
  }
}

rows=()
# One case on both meshes: its name, the number in its table row's first column, its label in
# the second, then its parameters.
study_case() {
    local name=$1 ratio=$2 label=$3
    shift 3
    local params="$*"
    # shellcheck disable=SC2086
    "$binary" onset $params --out "$work/$name-onset" >/dev/null
    k0=$(json "$work/$name-onset/onset.json" "['k0']")
    d_c=$(json "$work/$name-onset/onset.json" "['d_c']")
    length=$(python3 -c "import math; print($WAVELENGTHS * 2 * math.pi / $k0)")
    depth=$(python3 -c "print(max(50.0, $length))")
    d_max=$(python3 -c "print(round(min($d_c + $PAST_ONSET, 0.6), 4))")
    # Stage 1 below the onset (a contrast of 1000 wrinkles at d_c = 0.005, stage 1's default).
    d_start=$(python3 -c "print(round(min(0.005, $d_c / 2), 5))")
    for mesh in "${MESHES[@]}"; do
      read -r mesh_name per_wave layer substrate h0 <<<"$mesh"
      domain="--waves $WAVELENGTHS --length $length --depth $depth --nx $((WAVELENGTHS * per_wave)) --layer-elements $layer \
        --substrate-elements $substrate --h0 $h0 --imperfection -0.05 --max-step 0.001 --d-max $d_max \
        --d-start $d_start"
      [ "$mode" != long ] || mesh_name="long-$mesh_name"
      periodic=$work/$name-$mesh_name-periodic
      echo "$name ($mesh_name): k0 = $k0, d_c = $d_c, L = $length, to d = $d_max"
      # shellcheck disable=SC2086
      run "$periodic" $params $domain
      half_waves=$(python3 - "$periodic/secondary.json" <<'EOF'
import json, sys
try:
    changes = json.load(open(sys.argv[1]))["changes"]
except FileNotFoundError:
    changes = []
# The first change: the periodic wrinkle's secondary bifurcation.
print(changes[0]["mode_half_waves"] or "" if changes else "")
EOF
      )
      seeded=$work/$name-$mesh_name-seeded
      if [ -n "$half_waves" ]; then
        # shellcheck disable=SC2086
        run "$seeded" $params $domain --imperfection2 0.01 --imperfection2-waves \
          "$(python3 -c "print($half_waves / 2)")"
      fi
      rows+=("$ratio $label $mesh_name $k0 $d_c $periodic $seeded")
    done
}

if [ "$mode" = long ]; then
  # The low contrasts, where the literature has folds.
  for bulk in K3 K100; do
    for ratio in 5 10; do
      # shellcheck disable=SC2046
      study_case "mu$ratio-$bulk" "$ratio" "$bulk" \
        --set mu_l="$ratio" --set phi_m=1 --set phi_f=0 $(compressibility $bulk "$ratio")
    done
  done
else
  # The compressible cases of every contrast first: the exactly incompressible ones are the
  # slowest.
  for bulk in K3 K100 incompressible; do
    for ratio in "${CONTRASTS[@]}"; do
      # shellcheck disable=SC2046
      study_case "mu$ratio-$bulk" "$ratio" "$bulk" \
        --set mu_l="$ratio" --set phi_m=1 --set phi_f=0 $(compressibility $bulk "$ratio")
    done
  done
  # Table 1 (contrast 10, K / mu = 3) with its fibres along, at 45 degrees to and across the
  # compression.
  for beta in 0 0.7854 1.5708; do
    study_case "table1-beta$beta" 10 "table1-beta$beta" --set beta="$beta"
  done
fi

WAVELENGTHS=$WAVELENGTHS python3 - "$table" "${rows[@]}" <<'EOF'
import json, os, sys

def load(path):
    try:
        return json.load(open(path))
    except FileNotFoundError:
        return None

def stop(folder):
    log = folder + ".log"
    if not os.path.exists(log):
        return ""
    lines = [l for l in open(log) if l.startswith("error:")]
    return lines[-1].strip().split(" with ")[0].replace("error: ", "") if lines else ""

wrinkle = 2 * int(os.environ["WAVELENGTHS"])
out = [
    f"| mu_l/mu_s | K/mu | mesh | k0 | d_c | d_secondary | mode (half waves; {wrinkle} is the wrinkle) | the count back to zero after it (the path left the periodic branch) | seeded run ends at d | its troughs (plane, ..., plane) | branch |",
    "|---:|---|---|---:|---:|---|---:|---|---:|---|---|",
]
order = {"K3": 0, "K100": 1, "incompressible": 2}
rows = sorted(sys.argv[2:], key=lambda r: (float(r.split()[0]), order.get(r.split()[1], 3), r.split()[1], r.split()[2] != "coarse"))
missing = []
for row in rows:
    ratio, bulk, mesh, k0, d_c, periodic, seeded = row.split()
    bulk = {"K3": "3", "K100": "100", "incompressible": "inf"}.get(bulk) or "3 (Table 1, fibres at beta = " + bulk.removeprefix("table1-beta") + ")"
    if not os.path.exists(periodic + ".log"):
        missing.append(f"{ratio} (K/mu = {bulk}, {mesh})")
        continue
    first = load(periodic + "/secondary.json")
    changes = (first or {}).get("changes", [])
    returns = ", ".join(
        f"{c['d_before']:.4f}-{c['d_after']:.4f} (from {c['negative_before']})"
        for c in changes[1:]
        if c["negative_after"] == 0
    )
    if first is None:
        why = stop(periodic)
        secondary, mode = ("run failed: " + why if why else "not finished"), ""
    elif changes:
        c = changes[0]
        secondary, mode = f"{c['d_before']:.4f}-{c['d_after']:.4f}", str(c["mode_half_waves"] or "")
    else:
        ends = load(periodic + "/simulate.json")
        secondary, mode = "none to " + (f"{ends['d_reached']:.3f}" if ends else "the end"), ""
    path = load(seeded + "/secondary.json")
    summary = load(seeded + "/simulate.json")
    if path is None:
        why = stop(seeded)
        ends, troughs, kind = "", "", (
            "(no seeded run: no change)"
            if first is not None and not changes
            else f"(seeded run {why})" if why else "(seeded run not finished)"
        )
    else:
        ends = f"{summary['d_reached']:.4f}" if summary else ""
        troughs = ", ".join(f"{t:.2f}" for t in path["branch"]["trough_depths"])
        kind = path["branch"]["kind"]
        why = stop(seeded)
        if why:
            kind += f" ({why})"
    out.append(
        f"| {ratio} | {bulk} | {mesh} | {float(k0):.4f} | {float(d_c):.4f} | {secondary} | {mode} | {returns or '-'} | {ends} | {troughs} | {kind} |"
    )
if missing:
    out += ["", "Not run yet (`bench/period_doubling.sh` runs them): " + "; ".join(missing) + "."]
open(sys.argv[1], "w").write("\n".join(out) + "\n")
print("\n".join(out))
EOF

# The guide's pictures of what the path becomes: the contrast-100 bilayer (K = 100 mu, coarse)
# on two wavelengths, and contrast 5 (K = 3 mu) on eight.
if [ "$mode" = long ]; then
  picture=("$work/mu5-K3-long-coarse-seeded/fig7.png" period-doubling-long.png)
else
  picture=("$work/mu100-K100-coarse-seeded/fig7.png" period-doubling.png)
fi
if [ -f "${picture[0]}" ]; then
  cp "${picture[0]}" "$root/docs/guide/src/figures/${picture[1]}"
fi
