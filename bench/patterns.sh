#!/usr/bin/env bash
# Writes the table of the guide's page "Which pattern the fibres make"
# (docs/guide/src/results/patterns-table.md) and its pictures (docs/guide/src/figures/pattern-*.png)
# from `fiberfold pattern` runs: Table 1 under equibiaxial compression and under the layer's area
# growth in its surface, for fibres at beta = 0, pi/8, pi/4, pi/2 (psi = 0) and beta = pi/4,
# psi = 30 deg, each followed from its onset to d_c + 0.1 on the periodic patch one onset period
# square; then the box-size study of one case (1 x 1, 2 x 2 and 3 x 3 periods); then the map of
# patterns over the fibres' inclination beta and azimuth psi (docs/guide/src/results/patterns-map.md
# and figures/pattern-map.png).
#
#   bench/patterns.sh            (after cargo build --release; hours on 2 cores, most of them the
#                                 3 x 3 box: 109,620 unknowns, a 3.3 GB factor)
#   bench/patterns.sh table      (the ten paths only)
#   bench/patterns.sh boxes      (the box-size study only)
#   bench/patterns.sh map        (the map of patterns only)
#
# Runs are kept in $PATTERNS_WORK (default results/patterns-study): a case whose pattern.json is
# there is not run again, so the script resumes where it was stopped.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
binary=${FIBERFOLD:-$root/target/release/fiberfold}
work=${PATTERNS_WORK:-$root/results/patterns-study}
table=$root/docs/guide/src/results/patterns-table.md
map_table=$root/docs/guide/src/results/patterns-map.md
figures=$root/docs/guide/src/figures
[ -x "$binary" ] || { echo "no $binary: run cargo build --release first (or set FIBERFOLD)" >&2; exit 1; }
mkdir -p "$work"
what=${1:-all}

# name, load, then the parameters
CASES=(
  "compression-beta0         compression --set beta=0"
  "compression-beta22        compression --set beta=0.3926991"
  "compression-beta45        compression --set beta=0.7853982"
  "compression-beta90        compression --set beta=1.5707963"
  "compression-beta45-psi30  compression --set beta=0.7853982 --set psi=0.5235988"
  "growth-beta0              growth --set beta=0"
  "growth-beta22             growth --set beta=0.3926991"
  "growth-beta45             growth --set beta=0.7853982"
  "growth-beta90             growth --set beta=1.5707963"
  "growth-beta45-psi30       growth --set beta=0.7853982 --set psi=0.5235988"
)
# The pattern well past the onset: d_c + AFTER[-1].
AFTER=(0.02 0.05 0.1)

# The theory's d_c of a load and parameters (`onset --biaxial 1`).
theory_d_c() {
  local out=$work/onset-$1
  shift
  "$binary" onset --biaxial 1 --load "$@" --out "$out" >/dev/null
  python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['d_c'])" "$out/onset.json"
}

# Follows one case to d_c + 0.1 (unless done): name, periods, elements per wavelength, load, params.
follow() {
  local name=$1 periods=$2 epw=$3 load=$4
  shift 4
  local out=$work/$name
  [ -f "$out/pattern.json" ] && return 0
  local d_c
  d_c=$(theory_d_c "$name" "$load" "$@")
  local to
  to=$(python3 -c "print(round($d_c + ${AFTER[-1]}, 6))")
  echo "$name: d_c = $d_c, following to $to" >&2
  "$binary" pattern --load "$load" "$@" --periods "$periods" --elements-per-wavelength "$epw" \
    --follow-to "$to" --resume --out "$out" >>"$work/$name.log" 2>&1 || echo "  $name stopped: $(tail -1 "$work/$name.log")" >&2
}

if [ "$what" = all ] || [ "$what" = table ]; then
  for c in "${CASES[@]}"; do
    read -r name load params <<<"$c"
    # shellcheck disable=SC2086
    follow "$name" 1 6 "$load" $params
  done
fi
if [ "$what" = all ] || [ "$what" = boxes ]; then
  for periods in 1 2 3; do
    follow "boxes-compression-beta0-p$periods" "$periods" 4 compression --set beta=0
  done
fi
if [ "$what" = all ] || [ "$what" = map ]; then
  # Compression, equibiaxial; beta = 0, 30, 60, 90 deg against psi = 0, 22.5, 45 deg; each point
  # followed to its own d_c + 0.04 (a finished map is only assembled again).
  "$binary" pattern --x beta --x-from 0 --x-to 1.5707963 --x-points 4 --y psi --y-from 0 --y-to 0.7853982 \
    --y-points 3 --elements-per-wavelength 4 --substrate-elements 8 --follow-past 0.04 \
    --out "$work/beta-psi" >"$work/beta-psi.log" 2>&1
  cp "$work/beta-psi/map.png" "$figures/pattern-map.png"
  python3 - "$work/beta-psi/map.json" "$map_table" <<'MAP'
import json, math, sys

report = json.load(open(sys.argv[1]))
header = ["beta", "psi", "d_c theory", "theta0", "d_bif box", "unknowns", "pattern at d_c + 0.04", "branches left at d"]
lines = [
    "<!-- Written by bench/patterns.sh from its map run, replaced on each run: do not edit by hand. -->",
    "",
    "| " + " | ".join(header) + " |",
    "|" + "---|" * len(header),
]
for p in report["points"]:
    degrees = lambda radians: f"{math.degrees(radians):.1f}°"
    theta = "any" if p["theta0_degrees"] is None else f"{p['theta0_degrees']:.1f}°"
    if p["failed"] is not None:
        state = "failed: " + p["failed"]
    else:
        waves = ", ".join(f"{d['wave']['theta_degrees']:.0f}° {100 * d['share']:.0f} %" for d in p["directions"][:2])
        state = f"{p['pattern']}: {waves}; A = {p['amplitude']:.2f}"
        if p["stopped"] is not None:
            state += f" (stopped at d = {p['d']:.3f})"
    left = ", ".join(f"{d:.3f}" for d in p["branches_left"]) or "none"
    cells = [degrees(p["x"]), degrees(p["y"]), f"{p['d_c']:.4f}", theta, f"{p['d_bifurcation']:.4f}", str(p["unknowns"]), state, left]
    lines.append("| " + " | ".join(cells) + " |")
open(sys.argv[2], "w").write("\n".join(lines) + "\n")
print(f"wrote {sys.argv[2]}", file=sys.stderr)
MAP
fi
[ "$what" = map ] && exit 0

# The table, from the runs' pattern.json and pattern.csv.
python3 - "$work" "$table" "$figures" "${AFTER[*]}" <<'EOF'
import csv, json, os, shutil, sys

work, table, figures, after = sys.argv[1], sys.argv[2], sys.argv[3], [float(a) for a in sys.argv[4].split()]

def states(name):
    with open(os.path.join(work, name, "pattern.csv")) as f:
        return list(csv.DictReader(f))

def described(row):
    """The pattern of a state: its kind and its leading directions' wave vectors and shares."""
    if row is None:
        return "not reached"
    waves = []
    for i in ("1", "2"):
        if row["m" + i]:
            waves.append(f"({row['m' + i]}, {row['n' + i]}) {float(row['theta' + i + '_degrees']):.0f}° {100 * float(row['share' + i]):.0f} %")
    return f"{row['pattern']}: " + ", ".join(waves) + f"; A = {float(row['A']):.2f}"

def nearest(rows, d):
    """The last state at or before d (a state left unstable counts as the one reached)."""
    before = [r for r in rows if float(r["d"]) <= d + 1e-9]
    if not before or float(before[-1]["d"]) < d - 0.0051:
        return None
    return before[-1]

def row(name, label):
    directory = os.path.join(work, name)
    if not os.path.exists(os.path.join(directory, "pattern.json")):
        return None
    report = json.load(open(os.path.join(directory, "pattern.json")))
    rows = states(name)
    d_c = report["onset_theory"]["d_c"]
    theta = report["onset_theory"]["theta0_degrees"]
    path = report["path"]
    cells = [
        label,
        f"{d_c:.4f}",
        "any" if theta is None else f"{theta:.1f}°",
        f"{report['d_bifurcation']:.4f}",
        f"{report['patch']['length_x']:.1f} x {report['patch']['length_z']:.1f}, {report['unknowns']}",
    ]
    cells += [described(nearest(rows, d_c + a)) for a in after]
    left = ", ".join(f"{d:.3f}" for d, _ in path["branches_left"]) or "none"
    cells.append(left + ("" if path["stopped"] is None else f"; stopped at {path['d_reached']:.3f}"))
    return cells

header = ["case", "d_c theory", "theta0", "d_bif box", "box (H), unknowns"] + [f"d_c + {a}" for a in after] + ["branches left at d"]
lines = [
    "<!-- Written by bench/patterns.sh from its runs, replaced on each run: do not edit by hand. -->",
    "",
    "| " + " | ".join(header) + " |",
    "|" + "---|" * len(header),
]
for c in ["compression-beta0", "compression-beta22", "compression-beta45", "compression-beta90", "compression-beta45-psi30",
          "growth-beta0", "growth-beta22", "growth-beta45", "growth-beta90", "growth-beta45-psi30"]:
    load, rest = c.split("-", 1)
    label = {"beta0": "beta = 0", "beta22": "beta = pi/8", "beta45": "beta = pi/4", "beta90": "beta = pi/2",
             "beta45-psi30": "beta = pi/4, psi = 30°"}[rest]
    cells = row(c, f"{load}, {label}")
    if cells is not None:
        lines.append("| " + " | ".join(cells) + " |")
        picture = os.path.join(work, c, "state_top.png")
        if os.path.exists(picture):
            shutil.copy(picture, os.path.join(figures, f"pattern-{c}.png"))
lines += ["", "The box-size study (compression, beta = 0, 4 hexahedra per wavelength):", ""]
lines += ["| " + " | ".join(["periods"] + header[1:]) + " |", "|" + "---|" * len(header)]
for periods in (1, 2, 3):
    cells = row(f"boxes-compression-beta0-p{periods}", f"{periods} x {periods}")
    if cells is not None:
        lines.append("| " + " | ".join(cells) + " |")
        picture = os.path.join(work, f"boxes-compression-beta0-p{periods}", "state_top.png")
        if os.path.exists(picture):
            shutil.copy(picture, os.path.join(figures, f"pattern-boxes-p{periods}.png"))
open(table, "w").write("\n".join(lines) + "\n")
print(f"wrote {table}", file=sys.stderr)
EOF
