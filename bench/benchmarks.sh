#!/usr/bin/env bash
# Writes the guide's benchmarks page, docs/guide/src/benchmarks.md, from what this machine
# measures now: `fiberfold bench stability`, `fiberfold bench fe`, `fiberfold bench patch`,
# `fiberfold bench crease` (an isotropic bilayer at contrast 3), `fiberfold bench map` and,
# where FEniCSx is installed (bench/fenicsx/install.sh), the side-by-side comparisons
# bench/fenicsx/compare.sh on the coarse mesh and bench/fenicsx/compare_patch.sh on a small 3D
# patch. The page names the machine, the date and fiberfold's version, and is replaced on each run.
#
#   bench/benchmarks.sh            (after cargo build --release; about 20 minutes on 2 cores and
#                                   12 GB of memory for the largest patch)
#
# Run it on a quiet machine: the FEniCSx ratios are only meaningful side by side, in one run.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
binary=${FIBERFOLD:-$root/target/release/fiberfold}
page=$root/docs/guide/src/benchmarks.md
[ -x "$binary" ] || { echo "no $binary: run cargo build --release first (or set FIBERFOLD)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "bench stability" >&2
"$binary" bench stability --orientation-map 31 --out "$work/stability" >"$work/stability.log"
echo "bench fe" >&2
"$binary" bench fe --out "$work/fe" >"$work/fe.log"
echo "bench patch" >&2
"$binary" bench patch --periods 3 --out "$work/patch" >"$work/patch.log"
echo "bench crease" >&2
"$binary" bench crease --set mu_l=3 --set K_l=300 --set K_s=100 --set phi_m=1 --set phi_f=0 \
  --out "$work/crease" >"$work/crease.log"
echo "bench map" >&2
"$binary" bench map --out "$work/map" >"$work/map.log"
compared=no
if [ -x "${FENICSX_DIR:-$HOME/.cache/fiberfold-fenicsx-bench}/venv/bin/python" ]; then
  echo "side by side with FEniCSx" >&2
  FIBERFOLD=$binary "$root/bench/fenicsx/compare.sh" coarse 0.25 >"$work/compare.log"
  echo "side by side with FEniCSx, in three dimensions" >&2
  FIBERFOLD=$binary "$root/bench/fenicsx/compare_patch.sh" 4 0.12 >"$work/compare_patch.log"
  compared=yes
fi

# A page's own headings one level down, under this page's sections.
demote() { sed 's/^#/##/' "$1"; }
version=$("$binary" --version | awk '{print $2}')
{
  echo "<!-- Written by bench/benchmarks.sh, replaced on each run: do not edit by hand. -->"
  echo "# Benchmarks"
  echo
  echo "Measured by \`bench/benchmarks.sh\` on $(date -u +%Y-%m-%d), fiberfold $version, on"
  echo "$(lscpu | sed -n 's/^Model name: *//p' | head -1) ($(nproc) cores),"
  echo "$(free -g | awk '/^Mem:/ {print $2}') GiB of memory, $(uname -sr)."
  echo "Absolute times differ between machines; the FEniCSx ratio is measured side by side in one"
  echo "run. To measure on your machine, run the script, or the commands of"
  echo "[\`bench\`](reference/bench.md)."
  echo
  echo "## Side by side with FEniCSx"
  echo
  if [ $compared = yes ]; then
    echo "\`bench/fenicsx/compare.sh coarse 0.25\`: the same model on the same mesh (Table 1,"
    echo "beta = 45 deg, 4.5 waves, displacement element, no contact, to d = 0.25), FEniCSx 0.11"
    echo "with plain Newton and MUMPS on one core."
    echo
    echo '```text'
    cat "$work/compare.log"
    echo '```'
    echo
    echo "\`bench/fenicsx/compare_patch.sh 4 0.12\`: a patch in three dimensions (Table 1, beta = 45"
    echo "deg, psi = 0, equibiaxial compression, one onset wavelength square with symmetry sides, 4"
    echo "hexahedra per wavelength, 27-node displacement hexahedra, to d = 0.12, past the onset)."
    echo "fiberfold's time includes its search for the first bifurcation and the inertia of every"
    echo "state, which the reference does not do."
    echo
    echo '```text'
    cat "$work/compare_patch.log"
    echo '```'
  else
    echo "Not measured on this run: FEniCSx is not installed (\`bench/fenicsx/install.sh\`)."
  fi
  echo
  echo "## Linear stability"
  echo
  demote "$work/stability/bench_stability.md"
  echo
  echo "## Finite elements"
  echo
  demote "$work/fe/bench_fe.md"
  echo
  echo "## Three dimensions"
  echo
  echo "\`bench patch --periods 3\`: one Newton iteration of \`pattern\`'s periodic patch (Table 1,"
  echo "equibiaxial; 6 elements per wavelength, 2 + 12 through the thickness) of 1 x 1 to 3 x 3"
  echo "onset periods, at the homogeneous state of d = 0.05."
  echo
  cat "$work/patch/bench_patch.md"
  echo
  echo "## Crease onset and maps"
  echo
  echo "\`bench crease\`: the converged crease onset of an isotropic bilayer at contrast 3"
  echo "(\`K = 100 mu\`), where it comes just before the wrinkle; \`bench map\`: a 2 x 2 map, each"
  echo "point split into its linear theory, crease search and nonlinear run."
  echo
  demote "$work/crease/bench_crease.md"
  echo
  demote "$work/map/bench_map.md"
} >"$page.new"
mv "$page.new" "$page"
echo "wrote $page" >&2
