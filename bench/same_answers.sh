#!/usr/bin/env bash
# Same answers, bit for bit: run one list of commands with two fiberfold binaries and compare
# every CSV, JSON and VTU file they write.
#
#   bench/same_answers.sh OLD NEW OUT [case ...]
#
#   OLD, NEW  two fiberfold binaries (NEW may be "-": run OLD only, compare nothing)
#   OUT       output folder: OUT/old/<case>, OUT/new/<case> (each run's log and done marker
#             beside it: OUT/old/<case>.log, OUT/old/<case>.done)
#   case ...  a subset of the cases below (default: all, in this order)
#
# Environment:
#   REUSE_OLD=1   do not rerun OLD for a case whose OUT/old/<case>.done marker records the same
#                 command line and the same OLD binary (sha256): the slow old runs are done once
#   REUSE_NEW=1   the same for NEW (to compare existing runs again without rerunning them)
#   VTU_FATAL=0   report VTU/PVD differences but do not let them fail the run (default 1)
#
# Compared, per case (old against new):
#   *.csv   columns whose header names a timing (see TIMING_RE) are dropped, the rest compared
#           exactly as text, line by line;
#   *.json  loaded with python3, keys whose name is a timing deleted recursively, the rest
#           compared exactly (floats by repr: bit for bit; key order, int/float, -0.0 count);
#   in both, the run's own output folder inside a string is replaced by <OUT> first, so paths
#   of written files compare;
#   *.vtu, *.pvd  byte for byte, reported on a line of their own;
#   the exit codes of the two runs; a CSV/JSON/VTU file written by one run only.
# Not compared: PNG/SVG, the console output.
# Prints one line per case ("same" or the first difference) and exits 1 if any case differs.
set -euo pipefail

# ---- the cases: name, then the flags (no value contains a space) ----------------------------
CASES=(
  "sim-displacement  simulate --set beta=0.785398 --waves 4.5 --mesh coarse --d-max 0.25 --element displacement"
  "sim-mixed         simulate --set beta=0.785398 --waves 4.5 --mesh coarse --d-max 0.25 --element mixed"
  "fig7              simulate --set beta=0.785398 --waves 5 --mesh fine --d-max 0.48"
  "fig7-snap-coarse  simulate --set beta=0.785398 --waves 5 --mesh coarse --d-max 0.48 --stabilisation snap"
  "growth            simulate --load growth --waves 5 --mesh coarse --d-max 0.3"
  "ogden             simulate --set layer.law=ogden --set layer.alpha=-25 --set substrate.law=ogden --set substrate.alpha=-25 --waves 5 --mesh coarse --d-max 0.3"
  "bifurcation       bifurcation --set beta=0.785398 --mesh coarse"
  "crease            crease --set mu_l=1 --set K_l=100 --set K_s=100 --set phi_m=1 --set phi_f=0 --fold 0.5,1 --d-from 0.3 --d-to 0.38 --d-step 0.04 --no-convergence"
  "onset-biaxial     onset --biaxial 1"
  "map-point         map --x mu_l --x-from 10 --x-to 10 --x-points 1 --y beta --y-from 0.785398 --y-to 0.785398 --y-points 1"
)

# Keys (JSON) and column headers (CSV) that hold timings or other run-dependent values: matched
# case-insensitively against the whole name split at '_', '-', '.' and spaces (a token must
# match, so mu_s, K_s, outer, timestep... are kept). Override with the environment's TIMING_RE.
TIMING_RE=${TIMING_RE:-'^(time|times|timing|timings|timestamp|seconds|secs|elapsed|wall|date|started|finished|duration|path|paths|out|outdir|output|version|commit|git|threads|jobs|cores|cpus|host|hostname|pid|memory|rss|mb)$'}

usage() { sed -n '2,30p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
[[ $# -ge 3 ]] || usage
OLD=$1 NEW=$2 OUT=$3
shift 3
REUSE_OLD=${REUSE_OLD:-0}
REUSE_NEW=${REUSE_NEW:-0}
VTU_FATAL=${VTU_FATAL:-1}

abs_bin() { # an absolute path of an executable
  local b=$1
  [[ $b == */* ]] || b=$(command -v -- "$b" || true)
  [[ -n $b && -x $b ]] || { echo "not an executable: $1" >&2; exit 2; }
  realpath -- "$b"
}
OLD=$(abs_bin "$OLD")
[[ $NEW == - ]] || NEW=$(abs_bin "$NEW")
mkdir -p -- "$OUT"
OUT=$(realpath -- "$OUT")

declare -A FLAGS=()
ORDER=()
for entry in "${CASES[@]}"; do
  read -r name flags <<<"$entry"
  FLAGS[$name]=$flags
  ORDER+=("$name")
done
if [[ $# -gt 0 ]]; then
  for c in "$@"; do
    [[ -n ${FLAGS[$c]+x} ]] || { echo "unknown case: $c (cases: ${ORDER[*]})" >&2; exit 2; }
  done
  SELECTED=("$@")
else
  SELECTED=("${ORDER[@]}")
fi

# run SIDE BINARY CASE: the case into OUT/SIDE/CASE; prints its wall time
run_case() {
  local side=$1 bin=$2 name=$3
  local dir=$OUT/$side/$name marker=$OUT/$side/$name.done log=$OUT/$side/$name.log
  local -a flags
  read -r -a flags <<<"${FLAGS[$name]}"
  local cmd="${flags[*]} --out $dir"
  local sha
  sha=$(sha256sum -- "$bin" | cut -d' ' -f1)
  local reuse=$REUSE_OLD
  [[ $side == new ]] && reuse=$REUSE_NEW
  if [[ $reuse == 1 && -f $marker ]] &&
     grep -qxF "command=$cmd" "$marker" && grep -qxF "sha256=$sha" "$marker"; then
    printf '%-18s %s: reused (%s s)\n' "$name" "$side" "$(sed -n 's/^seconds=//p' "$marker")"
    return
  fi
  rm -rf -- "$dir" "$marker"
  mkdir -p -- "$OUT/$side"
  local t0 t1 rc=0
  t0=$(date +%s.%N)
  "$bin" "${flags[@]}" --out "$dir" >"$log" 2>&1 </dev/null || rc=$?
  t1=$(date +%s.%N)
  local secs
  secs=$(python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$t0" "$t1")
  {
    echo "command=$cmd"
    echo "binary=$bin"
    echo "sha256=$sha"
    echo "rc=$rc"
    echo "seconds=$secs"
    echo "finished=$(date -Is)"
  } >"$marker"
  printf '%-18s %s: exit %s in %s s\n' "$name" "$side" "$rc" "$secs"
}

for name in "${SELECTED[@]}"; do
  run_case old "$OLD" "$name"
  [[ $NEW == - ]] || run_case new "$NEW" "$name"
done
[[ $NEW == - ]] && exit 0

# ---- compare ---------------------------------------------------------------------------------
TIMING_RE=$TIMING_RE VTU_FATAL=$VTU_FATAL python3 - "$OUT" "${SELECTED[@]}" <<'PY'
import csv, io, json, os, re, sys

out, cases = sys.argv[1], sys.argv[2:]
timing = re.compile(os.environ["TIMING_RE"], re.I)
vtu_fatal = os.environ.get("VTU_FATAL", "1") != "0"

def is_timing(name):
    return any(timing.match(t) for t in re.split(r"[_\-. ]+", str(name)) if t)

def short(v, n=100):
    s = v if isinstance(v, str) else json.dumps(v)
    return s if len(s) <= n else s[:n] + "..."

def files(root, exts):
    got = set()
    for d, _, fs in os.walk(root):
        for f in fs:
            if f.lower().endswith(exts) and not f.startswith("."):
                got.add(os.path.relpath(os.path.join(d, f), root))
    return got

def norm_str(s, root):
    return s.replace(root, "<OUT>")

def clean(o, root):
    if isinstance(o, dict):
        return {k: clean(v, root) for k, v in o.items() if not is_timing(k)}
    if isinstance(o, list):
        return [clean(v, root) for v in o]
    if isinstance(o, str):
        return norm_str(o, root)
    return o

def first_json_diff(a, b, path="$"):
    if type(a) is not type(b):
        return path, a, b
    if isinstance(a, dict):
        if list(a) != list(b):
            for k in list(a) + list(b):
                if k not in a or k not in b:
                    return f"{path}.{k}", a.get(k, "<absent>"), b.get(k, "<absent>")
            return path + " (key order)", list(a), list(b)
        for k in a:
            d = first_json_diff(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list):
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_json_diff(x, y, f"{path}[{i}]")
            if d:
                return d
        if len(a) != len(b):
            return f"{path} (length)", len(a), len(b)
        return None
    if isinstance(a, float):
        return None if repr(a) == repr(b) else (path, repr(a), repr(b))
    return None if a == b else (path, a, b)

def cmp_json(fa, fb, ra, rb):
    def load(f, r):
        with open(f, "rb") as h:
            raw = h.read().decode("utf-8")
        return clean(json.loads(raw), r)
    try:
        a, b = load(fa, ra), load(fb, rb)
    except ValueError as e:
        return f"not JSON ({e})"
    d = first_json_diff(a, b)
    if d:
        return f"key {d[0]}: old={short(d[1])} new={short(d[2])}"
    return None

def cmp_csv(fa, fb, ra, rb):
    def load(f, r):
        with open(f, "rb") as h:
            text = h.read().decode("utf-8")
        rows = list(csv.reader(io.StringIO(text, newline="")))
        if not rows:
            return [], [], text.endswith("\n")
        header = rows[0]
        keep = [i for i, h in enumerate(header) if not is_timing(h)]
        body = [[norm_str(row[i], r) if i < len(row) else "<missing>" for i in keep] + [f"<{len(row)} fields>"] for row in rows]
        return [header[i] for i in keep], body, text.endswith("\n")
    ha, a, ea = load(fa, ra)
    hb, b, eb = load(fb, rb)
    if ha != hb:
        return f"header: old={short(','.join(ha))} new={short(','.join(hb))}"
    for n, (x, y) in enumerate(zip(a, b), start=1):
        if x != y:
            for j, (u, v) in enumerate(zip(x, y)):
                if u != v:
                    col = ha[j] if j < len(ha) else "field count"
                    return f"line {n}, column {col}: old={short(u)} new={short(v)}"
    if len(a) != len(b):
        return f"lines: old {len(a)}, new {len(b)}"
    if ea != eb:
        return "final newline"
    return None

def cmp_bytes(fa, fb):
    with open(fa, "rb") as h:
        a = h.read()
    with open(fb, "rb") as h:
        b = h.read()
    if a == b:
        return None
    n = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
    return f"first differing byte {n} (sizes {len(a)}, {len(b)})"

def marker(side, case):
    info = {}
    try:
        with open(os.path.join(out, side, case + ".done")) as h:
            for line in h:
                k, _, v = line.rstrip("\n").partition("=")
                info[k] = v
    except FileNotFoundError:
        pass
    return info

failed = False
for case in cases:
    ra, rb = os.path.join(out, "old", case), os.path.join(out, "new", case)
    ma, mb = marker("old", case), marker("new", case)
    times = f"[old {ma.get('seconds', '?')} s, new {mb.get('seconds', '?')} s]"
    diff = None
    if not ma or not mb:
        diff = "a run did not finish (no .done marker)"
    elif ma.get("rc") != mb.get("rc"):
        diff = f"exit code: old {ma.get('rc')}, new {mb.get('rc')}"
    checked = 0
    if diff is None:
        fa, fb = files(ra, (".csv", ".json")), files(rb, (".csv", ".json"))
        if fa != fb:
            only = sorted(fa ^ fb)[0]
            diff = f"{only}: written by the {'old' if only in fa else 'new'} run only"
        else:
            for f in sorted(fa):
                checked += 1
                pa, pb = os.path.join(ra, f), os.path.join(rb, f)
                d = cmp_csv(pa, pb, ra, rb) if f.lower().endswith(".csv") else cmp_json(pa, pb, ra, rb)
                if d:
                    diff = f"{f}: {d}"
                    break
    if diff is None:
        print(f"{case:<18} same ({checked} csv/json) {times}")
    else:
        failed = True
        print(f"{case:<18} DIFF {diff} {times}")
    # VTU and PVD, byte for byte, on a line of their own
    va, vb = files(ra, (".vtu", ".pvd")), files(rb, (".vtu", ".pvd"))
    if not va and not vb:
        continue
    vdiff = None
    if va != vb:
        only = sorted(va ^ vb)[0]
        vdiff = f"{only}: written by the {'old' if only in va else 'new'} run only"
    else:
        for f in sorted(va):
            d = cmp_bytes(os.path.join(ra, f), os.path.join(rb, f))
            if d:
                vdiff = f"{f}: {d}"
                break
    if vdiff is None:
        print(f"{case:<18} vtu same ({len(va)} vtu/pvd files)")
    else:
        failed = failed or vtu_fatal
        print(f"{case:<18} vtu DIFF {vdiff}")
sys.exit(1 if failed else 0)
PY
