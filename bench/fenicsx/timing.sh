# Shared by the scripts that time fiberfold against the FEniCSx reference (sourced, not run,
# after setting `here` to bench/fenicsx): fiberfold's `binary` (FIBERFOLD, or the release build)
# and the reference's `venv` (FENICSX_DIR), both checked. The scripts then set `work` (a scratch
# folder holding fiberfold.time from /usr/bin/time -f "%e %M") and `reference` (the reference's
# command line without --d-max and --out).

root=$(cd "$here/../.." && pwd)
binary=${FIBERFOLD:-$root/target/release/fiberfold}
venv=${FENICSX_DIR:-$HOME/.cache/fiberfold-fenicsx-bench}/venv
[ -x "$binary" ] || { echo "no $binary: run cargo build --release first (or set FIBERFOLD)" >&2; exit 1; }
[ -x "$venv/bin/python" ] || { echo "FEniCSx is not installed: run $here/install.sh" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (Debian package time)" >&2; exit 1; }

# Runs the reference to D_MAX into $work/fenicsx.csv, timed into $work/fenicsx.time. Form
# compilation is cached after a first call: it is warmed first, so that the solve alone is timed.
time_reference() {
  OMP_NUM_THREADS=1 "${reference[@]}" --d-max 0.005 --out "$work/warm.csv" >/dev/null 2>&1
  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 /usr/bin/time -f "%e %M" -o "$work/fenicsx.time" \
    "${reference[@]}" --d-max "$1" --out "$work/fenicsx.csv" >"$work/fenicsx.log" 2>&1 || true
  read -r ff_seconds ff_kb <"$work/fiberfold.time"
  read -r fx_seconds fx_kb <"$work/fenicsx.time"
}

# Prints both programs' wall time, peak memory and the last d of their curves: fiberfold's CSV
# (first column d), then a note after the reference's line.
print_times() {
  local reached_fiberfold reached_fenicsx
  reached_fiberfold=$(tail -1 "$1" | cut -d, -f1)
  reached_fenicsx=$(tail -1 "$work/fenicsx.csv" | cut -d, -f1)
  printf "fiberfold: %7.1f s  %5d MB  reached d = %s\n" "$ff_seconds" $((ff_kb / 1024)) "$reached_fiberfold"
  printf "FEniCSx:   %7.1f s  %5d MB  reached d = %s%s\n" "$fx_seconds" $((fx_kb / 1024)) "$reached_fenicsx" "${2:-}"
}
