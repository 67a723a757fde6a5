"""A small study with the fiberfold Python package: the onset against the fibre angle, one
coarse simulation, and a plot (if matplotlib is installed).

    python examples/python_study.py [OUTPUT_FOLDER]
"""

import sys
from pathlib import Path

import numpy as np

import fiberfold

out = Path(sys.argv[1] if len(sys.argv) > 1 else "results/python_study")
out.mkdir(parents=True, exist_ok=True)

params = fiberfold.Parameters()  # Table 1
betas = np.linspace(0.0, np.pi / 2, 7)
onsets = fiberfold.sweep(params, "beta", betas)
print("onset against beta (mu_f = 10):")
for beta, k0, d_c in zip(onsets["value"], onsets["k0"], onsets["d_c"]):
    print(f"  beta = {beta:.4f}  k0 = {k0:.4f}  d_c = {d_c:.4f}")

run = fiberfold.simulate(params.replace(beta=np.pi / 4), waves=4.5, mesh="coarse", d_max=0.2)
print(f"simulate: {run.accepted_steps} states to d = {run.d_reached:.3f}; "
      f"steepest A' at d = {run.onset['d_steepest']:.4f} (linear theory {run.onset['d_linear_theory']:.4f})")
run.state.write_vtu(out / "final.vtu")

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib not installed: no plot")
else:
    fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.5))
    left.plot(onsets["value"], onsets["d_c"], "o-")
    left.set_xlabel("fibre angle beta (rad)")
    left.set_ylabel("critical compression d_c")
    right.plot(run.amplitude["d"], run.amplitude["A"])
    right.set_xlabel("end-shortening d")
    right.set_ylabel("amplitude A / H")
    fig.tight_layout()
    fig.savefig(out / "python_study.png", dpi=100)
    print(f"wrote {out / 'python_study.png'}")
