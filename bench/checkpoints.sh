#!/usr/bin/env bash
# The cost of simulate's checkpoints on the fine Fig. 7 run: the same command with checkpoints
# off (--checkpoint-every 0) and at the default interval, back to back, ROUNDS times, on one
# machine.
#
#   bench/checkpoints.sh BINARY OUT [ROUNDS]
#
# Writes OUT/checkpoints.md: each run's wall time and, with checkpoints, how many were written,
# the last one's size and the time spent writing them (simulate.json's `checkpoints`); the ratio
# of the mean wall times; and whether both runs computed the same path (amplitude.csv without
# its timing column: it must, a checkpoint does not change the path).
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 BINARY OUT [ROUNDS]" >&2; exit 2; }
bin=$1
out=$2
rounds=${3:-1}
args=(simulate --set beta=0.785398 --waves 5 --mesh fine --d-max 0.48)
mkdir -p "$out"
for round in $(seq "$rounds"); do
  for mode in off on; do
    flags=()
    [ "$mode" = off ] && flags=(--checkpoint-every 0)
    echo "round $round, checkpoints $mode" >&2
    "$bin" "${args[@]}" "${flags[@]}" --out "$out/$mode-$round" > "$out/$mode-$round.log" 2>&1
  done
done
python3 - "$out" "$rounds" "${args[*]}" <<'PY'
import csv, json, statistics, sys
out, rounds, command = sys.argv[1], int(sys.argv[2]), sys.argv[3]

def path(run):
    with open(f"{out}/{run}/amplitude.csv") as f:
        rows = list(csv.reader(f))
    keep = [i for i, name in enumerate(rows[0]) if "seconds" not in name]
    return [[row[i] for i in keep] for row in rows]

lines = [
    "# The cost of checkpoints",
    "",
    f"`fiberfold {command}`, with `--checkpoint-every 0` (off) and at the default interval (on), back to back.",
    "",
    "| round | off: wall s | on: wall s | on / off | checkpoints | last one, MB | writing them, s | same path |",
    "|---|---|---|---|---|---|---|---|",
]
walls = {"off": [], "on": []}
for r in range(1, rounds + 1):
    summary = {m: json.load(open(f"{out}/{m}-{r}/simulate.json")) for m in ("off", "on")}
    for m in walls:
        walls[m].append(summary[m]["wall_seconds"])
    c = summary["on"]["checkpoints"]
    same = path(f"off-{r}") == path(f"on-{r}")
    lines.append(
        f"| {r} | {walls['off'][-1]:.1f} | {walls['on'][-1]:.1f} | {walls['on'][-1] / walls['off'][-1]:.4f} "
        f"| {c['written']} | {c['bytes'] / 1e6:.2f} | {c['seconds']:.3f} | {'yes' if same else 'NO'} |"
    )
mean = {m: statistics.mean(w) for m, w in walls.items()}
lines += ["", f"Mean wall time: off {mean['off']:.1f} s, on {mean['on']:.1f} s, ratio {mean['on'] / mean['off']:.4f}."]
open(f"{out}/checkpoints.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
