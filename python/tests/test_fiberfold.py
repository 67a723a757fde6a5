"""Tests of the Python package against independent values, the CLI, and its error contract."""

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import fiberfold

ROOT = Path(__file__).resolve().parents[2]
TINY = dict(nx=20, layer_elements=1, substrate_elements=6)


def cli_binary() -> Path:
    """The CLI built from the same library (`cargo build --release` or `cargo test --release`)."""
    path = Path(os.environ.get("FIBERFOLD_BIN", ROOT / "target" / "release" / "fiberfold"))
    if not path.is_file():
        pytest.fail(f"no fiberfold binary at {path}: run `cargo build --release` first or set FIBERFOLD_BIN")
    return path


def test_biot_surface_instability_of_a_nearly_incompressible_half_space():
    # No contrast, no fibres, K = 10^4 mu: Biot's lambda = 0.5437 at every k.
    p = fiberfold.Parameters(mu_l=1.0, K_l=1e4, K_s=1e4, phi_m=1.0, phi_f=0.0)
    result = fiberfold.dispersion(p, [0.3, 1.0, 2.5])
    assert result["lambda1_c"].shape == (3,)
    assert np.allclose(result["lambda1_c"], 0.5437, atol=2e-4)
    assert result["k_without_root"].size == 0


def test_onset_without_fibre_stiffness_matches_the_paper():
    o = fiberfold.onset(fiberfold.Parameters(mu_f=0.0))
    assert abs(o.k0 - 0.5515) < 1e-4
    assert set(o.as_dict()) >= {"k0", "d_c", "lambda1_c", "d_ellipticity_loss", "wavelength", "method", "parameters"}
    assert o.lambda1_c == pytest.approx(1.0 - o.d_c, abs=1e-15)


def test_growth_is_a_load_uniform_growth_the_compression_of_the_grown_body():
    compressed = fiberfold.onset(fiberfold.Parameters(beta=0.5))
    grown = fiberfold.onset(fiberfold.Parameters(beta=0.5, load="uniform_growth"))
    assert compressed.load == "compression" and compressed.g_c is None
    assert grown.load == "uniform_growth" and grown.g_c == pytest.approx(1.0 / (1.0 - grown.d_c), rel=1e-14)
    # The grown body compressed by 1/g: the same strain, at the wavenumber k/g.
    assert grown.d_c == pytest.approx(compressed.d_c, abs=1e-9)
    assert grown.k0 / grown.g_c == pytest.approx(compressed.k0, rel=1e-6)
    with pytest.raises(ValueError, match="growth_layer"):
        fiberfold.onset(fiberfold.Parameters(load="growth", growth_layer=1.3))
    with pytest.raises(TypeError, match="load"):
        fiberfold.Parameters(load=1.0)


def test_equibiaxial_half_space_is_biot_in_every_direction_and_inclined_fibres_orient_the_crests():
    # Incompressible neo-Hookean half-space, equibiaxial: x^3 + x^2 + 3x - 1 = 0, x = lambda^3.
    roots = np.roots([1.0, 1.0, 3.0, -1.0])
    x = roots[np.isreal(roots)].real[0]
    half_space = fiberfold.Parameters(mu_l=1.0, phi_m=1.0, phi_f=0.0, incompressible=True)
    for theta in (0.0, 0.9):
        d = fiberfold.dispersion(half_space, [0.5, 2.0], biaxial=1.0, theta=theta)["d_c"]
        assert np.allclose(d, 1.0 - np.cbrt(x), atol=1e-8)
    o = fiberfold.onset(fiberfold.Parameters(beta=np.pi / 4, psi=np.pi / 6), biaxial=1.0)
    assert o.theta0 == pytest.approx(np.pi / 6 + np.pi / 2, abs=1e-4)
    assert o.direction_spread > 1e-3 and o.biaxial == 1.0
    assert fiberfold.onset(fiberfold.Parameters()).theta0 == 0.0
    with pytest.raises(ValueError, match="biaxial"):
        fiberfold.onset(fiberfold.Parameters(), biaxial=2.0)


def test_homogeneous_state_is_stress_free_at_rest_and_has_the_csv_columns():
    h = fiberfold.homogeneous(fiberfold.Parameters(), np.array([0.0, 0.1, 0.2]))
    assert list(h) == [
        "d", "lambda1", "lambda2_layer", "lambda2_substrate", "J_layer", "J_substrate",
        "sigma11_layer", "sigma22_layer", "sigma33_layer",
        "sigma11_substrate", "sigma22_substrate", "sigma33_substrate",
        "growth_layer", "growth_substrate",
    ]
    assert all(v.dtype == np.float64 and v.shape == (3,) for v in h.values())
    assert np.allclose(h["lambda1"], [1.0, 0.9, 0.8])
    assert abs(h["sigma11_layer"][0]) < 1e-12
    # Uniaxial compression: sigma22 = 0 in both layers (free top surface).
    assert np.allclose(h["sigma22_layer"], 0.0, atol=1e-9)


def test_sweep_matches_single_onsets():
    p = fiberfold.Parameters()
    s = fiberfold.sweep(p, "beta", [0.0, 0.7], series=("mu_f", [1.0, 10.0]))
    assert s["value"].tolist() == [0.0, 0.7, 0.0, 0.7]
    assert s["series"].tolist() == [1.0, 1.0, 10.0, 10.0]
    single = fiberfold.onset(p.replace(beta=0.7, mu_f=10.0))
    assert s["k0"][3] == pytest.approx(single.k0, rel=1e-6)
    assert s["d_c"][3] == pytest.approx(single.d_c, rel=1e-6)


def test_parameters_round_trip_through_toml(tmp_path):
    p = fiberfold.Parameters(beta=0.5, mu_f=20.0, tension_only=True)
    path = tmp_path / "p.toml"
    path.write_text(p.to_toml())
    assert fiberfold.Parameters.from_toml(path) == p
    assert p.beta == 0.5 and p.tension_only is True
    assert p.to_dict()["mu_f"] == 20.0


def test_simulate_gives_the_cli_curve(tmp_path):
    p = fiberfold.Parameters(beta=0.785398)
    result = fiberfold.simulate(p, 4.5, d_max=0.05, **TINY)
    out = tmp_path / "cli"
    subprocess.run(
        [str(cli_binary()), "simulate", "--set", "beta=0.785398", "--waves", "4.5", "--nx", "20",
         "--layer-elements", "1", "--substrate-elements", "6", "--d-max", "0.05", "--out", str(out)],
        check=True, capture_output=True,
    )
    with open(out / "amplitude.csv") as f:
        rows = list(csv.DictReader(f))
    assert list(result.amplitude) == list(rows[0])
    for column in ["d", "A", "strain_energy", "min_J", "residual"]:
        cli = np.array([float(r[column]) for r in rows])
        ours = result.amplitude[column]
        assert ours.shape == cli.shape
        assert np.allclose(ours, cli, rtol=1e-12, atol=1e-15), column
    # The summary is simulate.json's, but for wall times and the files written.
    with open(out / "simulate.json") as f:
        written = json.load(f)
    assert set(result.summary) == set(written)
    assert result.summary["files"] == [] and written["files"]
    assert without_times_and_files(result.summary) == without_times_and_files(written)


def without_times_and_files(value):
    """`value` without wall times, timings and file names (which differ between two runs)."""
    if isinstance(value, dict):
        return {
            k: without_times_and_files(v)
            for k, v in value.items()
            if "seconds" not in k and k not in ("files", "mode_file", "totals", "checkpoints")
        }
    if isinstance(value, list):
        return [without_times_and_files(v) for v in value]
    return value


class Stop(Exception):
    pass


def test_simulate_into_a_folder_resumes_from_its_checkpoint(tmp_path):
    p = fiberfold.Parameters(beta=0.785398)
    run = dict(d_max=0.06, checkpoint_every=1, **TINY)
    whole = fiberfold.simulate(p, 4.5, out=tmp_path / "whole", **run)
    assert (tmp_path / "whole" / "checkpoint.bin").is_file()
    assert whole.summary["checkpoints"]["written"] == len(whole.amplitude["d"]) - 1

    def stop_past(info):
        if info["event"] == "step" and info["d"] > 0.03:
            raise Stop()

    folder = tmp_path / "stopped"
    with pytest.raises(Stop):
        fiberfold.simulate(p, 4.5, out=folder, progress=stop_past, **run)
    said = []
    resumed = fiberfold.simulate(p, 4.5, out=folder, resume=True, progress=said.append, **run)
    assert any(e.get("message", "").startswith("resuming at d = 0.0") for e in said), said
    for column in whole.amplitude:
        if "seconds" not in column:
            assert list(resumed.amplitude[column]) == list(whole.amplitude[column]), column
    with pytest.raises(ValueError, match="out"):
        fiberfold.simulate(p, 4.5, resume=True, **run)


def test_arc_length_reaches_displacement_controls_state():
    # Where d rises along the path, both methods reach the same equilibrium at d_max.
    plain = dict(d_max=0.05, contact=False, stabilisation="none", **TINY)
    control = fiberfold.simulate(fiberfold.Parameters(), 4.5, **plain)
    arc = fiberfold.simulate(fiberfold.Parameters(), 4.5, continuation="arc-length", **plain)
    assert arc.amplitude["d"][-1] == 0.05
    assert np.all(np.diff(arc.amplitude["d"]) > 0)
    assert abs(arc.amplitude["A"][-1] - control.amplitude["A"][-1]) <= 1e-10
    with pytest.raises(ValueError, match="continuation"):
        fiberfold.simulate(fiberfold.Parameters(), 4.5, continuation="arc-length", d_max=0.05, **TINY)


def test_simulate_arrays_have_the_documented_shapes():
    events = []
    result = fiberfold.simulate(fiberfold.Parameters(), 4.5, d_max=0.02, progress=events.append, **TINY)
    n = len(result.amplitude["d"])
    assert n == result.accepted_steps and n > 0
    assert all(v.dtype == np.float64 and v.shape == (n,) for v in result.amplitude.values())
    state = result.state
    points, cells = state.points, state.cells
    assert points.dtype == np.float64 and points.shape[1] == 3 and np.all(points[:, 2] == 0.0)
    assert cells.dtype == np.int64 and cells.shape[1] == 9 and cells.max() < len(points)
    assert state.point_data["displacement"].shape == (len(points), 3)
    assert np.array_equal(state.deformed_points, points + state.point_data["displacement"])
    assert state.cell_data["cauchy_stress"].shape == (len(cells), 6)
    assert state.cell_data["J"].shape == (len(cells),)
    assert np.all(state.cell_data["J"] > 0)
    assert result.completed and result.stopped is None
    assert {e["event"] for e in events} >= {"stage", "step"}
    assert result.onset["k"] == pytest.approx(result.k)


def test_state_writes_a_vtu(tmp_path):
    result = fiberfold.simulate(fiberfold.Parameters(), 4.5, d_max=0.01, **TINY)
    path = tmp_path / "final.vtu"
    result.state.write_vtu(path)
    text = path.read_text()
    assert 'NumberOfPoints="%d"' % len(result.state.points) in text


def test_bad_values_raise_value_error_naming_the_parameter():
    with pytest.raises(ValueError, match="mu_l"):
        fiberfold.Parameters(mu_l=-1.0)
    with pytest.raises(ValueError, match="phi_f"):
        fiberfold.Parameters(phi_f=float("nan"))
    with pytest.raises(ValueError, match="unknown parameter `muu`"):
        fiberfold.Parameters(muu=1.0)
    with pytest.raises(ValueError, match="`d`"):
        fiberfold.homogeneous(fiberfold.Parameters(), [0.1, 1.5])
    with pytest.raises(ValueError, match="`k`"):
        fiberfold.dispersion(fiberfold.Parameters(), [-1.0])
    with pytest.raises(ValueError, match="waves"):
        fiberfold.simulate(fiberfold.Parameters(), 4.3, d_max=0.02, **TINY)
    with pytest.raises(ValueError, match="mesh"):
        fiberfold.simulate(fiberfold.Parameters(), 4.5, mesh="huge")
    with pytest.raises(ValueError, match="method"):
        fiberfold.onset(fiberfold.Parameters(), method="guess")


def test_wrong_types_raise_type_error():
    with pytest.raises(TypeError):
        fiberfold.Parameters(mu_l="ten")
    with pytest.raises(TypeError):
        fiberfold.Parameters(beta=True)
    with pytest.raises(TypeError):
        fiberfold.Parameters(tension_only=1)
    with pytest.raises(TypeError):
        fiberfold.onset({"mu_l": 10})
    with pytest.raises(TypeError):
        fiberfold.simulate(fiberfold.Parameters(), "four")
    with pytest.raises(TypeError):
        fiberfold.sweep(fiberfold.Parameters(), 3, [1.0])


def test_solver_failure_carries_the_path_so_far():
    # Steps of 0.1 that may not be cut: the path stops early.
    with pytest.raises(fiberfold.SolverError) as caught:
        fiberfold.simulate(fiberfold.Parameters(), 4.5, d_max=0.6, max_step=0.1, min_step=0.1, **TINY)
    result = caught.value.result
    assert 0.005 <= result.d_reached < 0.6
    assert len(result.amplitude["d"]) >= 1 and not result.completed
    assert np.all(np.isfinite(result.amplitude["A"]))


def test_an_exception_in_the_progress_callback_stops_the_run():
    def stop(event):
        if event["event"] == "step":
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        fiberfold.simulate(fiberfold.Parameters(), 4.5, d_max=0.3, **TINY, progress=stop)


def test_ctrl_c_interrupts_a_long_run_within_a_second():
    # Ctrl-C from outside, as a terminal sends it: another process signals this one after 1 s.
    # Python's own handler is put in place first: a runner started in the background inherits
    # SIGINT ignored, and then Ctrl-C rightly interrupts nothing.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    start = time.monotonic()
    killer = subprocess.Popen(["sh", "-c", f"sleep 1; kill -INT {os.getpid()}"])
    try:
        with pytest.raises(KeyboardInterrupt):
            fiberfold.simulate(fiberfold.Parameters(), 4.5, mesh="coarse", d_max=0.9)
    finally:
        killer.wait()
        signal.signal(signal.SIGINT, previous)
    assert time.monotonic() - start < 2.0


def test_example_study_runs(tmp_path):
    script = ROOT / "examples" / "python_study.py"
    done = subprocess.run([sys.executable, str(script), str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "onset against beta" in done.stdout


def test_onset_of_a_soft_layer_is_the_long_wave_limit():
    o = fiberfold.onset(fiberfold.Parameters(mu_l=1.5, K_l=4.5))
    assert o.minimum == "long_wave" and o.k0 == 0.0 and o.wavelength is None
    assert fiberfold.onset(fiberfold.Parameters()).minimum == "interior"


def test_bifurcation_of_the_discretised_perfect_system_meets_the_linear_theory():
    # Without fibres, coarse mesh: the FE bifurcation within 1e-3 of min_m d_c(m pi / 50).
    r = fiberfold.bifurcation(fiberfold.Parameters(phi_m=1.0, phi_f=0.0), mesh="coarse")
    assert abs(r["d_bifurcation"] / r["d_linear_theory_min"] - 1.0) < 1e-3
    assert r["k_mode"] > 0


def test_incompressible_tissue_with_the_mixed_element():
    # Exactly incompressible, no fibres: Biot's half-space in the linear theory, and the FE
    # bifurcation of the bilayer within 2e-4 of it with the mixed element (the default), which
    # it needs.
    p = fiberfold.Parameters(phi_m=1.0, phi_f=0.0, incompressible=True)
    assert p.incompressible is True
    z = min(r.real for r in np.roots([1.0, 1.0, 3.0, -1.0]) if abs(r.imag) < 1e-12)  # Biot's cubic
    assert abs(fiberfold.onset(p.replace(mu_l=1.0)).d_c - (1.0 - np.sqrt(z))) < 1e-7
    r = fiberfold.bifurcation(p, mesh="coarse")
    assert r["mesh"]["element"] == "mixed"
    assert abs(r["relative_difference"]) < 2e-4
    with pytest.raises(ValueError, match="element"):
        fiberfold.bifurcation(p, mesh="coarse", element="displacement")
    with pytest.raises(ValueError, match="element"):
        fiberfold.bifurcation(p, mesh="coarse", element="hybrid")
    run = fiberfold.simulate(p.replace(beta=0.785398), 4.5, d_max=0.02, element="mixed", **TINY)
    assert run.completed and run.element == "mixed"
    assert np.all(np.isfinite(run.state.cell_data["pressure"]))


def test_crease_onset_of_a_soft_layer():
    p = fiberfold.Parameters(mu_l=1.5, K_l=4.5)
    mesh = dict(nx=24, layer_elements=2, substrate_elements=12, layer_grading=1.0, convergence=False)
    # Its wrinkle comes first: the scan ends 0.01 past the wrinkling onset.
    r = fiberfold.crease(p, [1.0], d_from=0.2, d_to=0.3, **mesh)
    assert r["first"] == "wrinkle" and r["d_crease"] is None and r["scan_ends_past_wrinkle"]
    assert abs(r["scan"]["to"] - (r["d_wrinkle"] + 0.01)) < 1e-12
    # Past it, the crease's own threshold.
    r = fiberfold.crease(p, [1.0], d_from=0.2, d_to=0.3, beyond_wrinkle=True, **mesh)
    assert 0.2 < r["d_crease"] < 0.3 and r["fold_length"] == 1.0
    with pytest.raises(ValueError, match="fold"):
        fiberfold.crease(p, [0.0])
    with pytest.raises(ValueError, match="a keyword of crease"):
        fiberfold.crease(p, [1.0], fold=2)
    with pytest.raises(TypeError, match="`nx`"):
        fiberfold.crease(p, [1.0], nx="many")


def test_crease_takes_the_cli_options_with_the_cli_defaults():
    defaults = fiberfold.crease_defaults()
    help_text = subprocess.run([str(cli_binary()), "crease", "--help"], capture_output=True, text=True).stdout
    flags = {"folds": "--fold", "convergence": "--no-convergence"}
    for name in defaults:
        assert flags.get(name, "--" + name.replace("_", "-")) in help_text, name
    assert defaults["folds"] == [0.5, 1.0, 2.0] and defaults["convergence"] is True
    assert defaults["element"] == "mixed" and defaults["nx"] == 24 and defaults["criterion"] == "held"


def test_laws_by_dotted_keys_or_tables_round_trip_and_give_their_onset():
    ogden = fiberfold.Parameters(**{"layer.law": "ogden", "layer.alpha": -25.0})
    same = fiberfold.Parameters(layer={"law": "ogden", "alpha": [-25]})
    assert ogden == same
    d = ogden.to_dict()
    assert d["layer.law"] == "ogden" and d["layer.alpha"] == [-25.0] and d["layer.mu"] == [10.0]
    assert fiberfold.Parameters(**d) == ogden
    assert getattr(ogden, "layer.law") == "ogden"
    # Mooney-Rivlin with c2 = 0 and c1 = mu_l / 2 is Table 1's neo-Hookean layer.
    mooney = fiberfold.Parameters(**{"layer.law": "mooney_rivlin", "layer.c1": 5.0, "layer.c2": 0.0})
    assert abs(fiberfold.onset(mooney).d_c - fiberfold.onset(fiberfold.Parameters()).d_c) < 1e-9
    with pytest.raises(ValueError, match="layer.alpha"):
        fiberfold.Parameters(**{"layer.law": "ogden"})
    with pytest.raises(ValueError, match=r"fibres.kappa.*\[0, 1/3\]"):
        fiberfold.Parameters(fibres={"law": "hgo", "k1": 1.0, "k2": 1.0, "kappa": 0.5})
    with pytest.raises(TypeError):
        fiberfold.Parameters(**{"layer.law": 3})


def test_the_type_stub_matches_the_native_module():
    import ast
    import inspect
    from pathlib import Path

    import fiberfold._fiberfold as native

    stub = ast.parse((Path(fiberfold.__file__).parent / "_fiberfold.pyi").read_text())
    functions = {f.name: f for f in stub.body if isinstance(f, ast.FunctionDef)}
    exported = {n for n in dir(native) if inspect.isbuiltin(getattr(native, n))}
    assert set(functions) == exported, (set(functions) ^ exported)
    for name, f in functions.items():
        stubbed = [a.arg for a in f.args.args + f.args.kwonlyargs]
        actual = list(inspect.signature(getattr(native, name)).parameters)
        assert stubbed == actual, (name, stubbed, actual)
    # The attributes the stub declares on Parameters are the flat keys the library lists.
    parameters = next(c for c in stub.body if isinstance(c, ast.ClassDef) and c.name == "Parameters")
    declared = [s.target.id for s in parameters.body if isinstance(s, ast.AnnAssign)]
    flat = [k for k in fiberfold.Parameters().to_dict() if "." not in k]
    assert declared == flat, (declared, flat)


def test_simulate_takes_the_cli_options_with_the_cli_defaults():
    defaults = fiberfold.simulate_defaults()
    # The options of `fiberfold simulate --help`, by their flag names.
    help_text = subprocess.run([str(cli_binary()), "simulate", "--help"], capture_output=True, text=True).stdout
    negated = {"contact": "--no-contact", "inertia": "--no-inertia"}
    for name in defaults:
        flag = negated.get(name, "--" + name.replace("_", "-"))
        assert flag in help_text, name
    assert defaults["d_max"] == 0.3 and defaults["mesh"] == "coarse" and defaults["stabilisation"] == "viscous"
    with pytest.raises(ValueError, match="bogus for `keyword`"):
        fiberfold.simulate(fiberfold.Parameters(), 4.5, bogus=1)
    with pytest.raises(TypeError, match="`d_max`"):
        fiberfold.simulate(fiberfold.Parameters(), 4.5, d_max="far")
    with pytest.raises(TypeError, match="`nx`"):
        fiberfold.simulate(fiberfold.Parameters(), 4.5, nx=2.5)


def test_the_fenicsx_comparison_reads_the_imperfect_mesh_of_a_run(tmp_path):
    # bench/fenicsx/wrinkle.py solves on fiberfold's mesh, read (by reference.py) from a run's
    # first snapshot: its points are the reference coordinates with the imperfection
    # (docs/model.md 8.4).
    import importlib.util

    spec = importlib.util.spec_from_file_location("reference", ROOT / "bench" / "fenicsx" / "reference.py")
    reference = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(reference)
    out = tmp_path / "run"
    subprocess.run(
        [str(cli_binary()), "simulate", "--waves", "4.5", "--nx", "20", "--layer-elements", "1",
         "--substrate-elements", "6", "--d-max", "0.01", "--out", str(out)],
        check=True, capture_output=True,
    )
    points, cells = reference.read_vtu(out / "simulate_0000.vtu", 9, 2)
    assert cells.shape == (20 * 7, 9) and points.shape == (41 * 15, 2)
    assert cells.max() == len(points) - 1
    k = 2 * np.pi * 4.5 / 50.0
    top = points[np.isclose(points[:, 1], 1.0 + 0.05 * np.cos(k * points[:, 0]), atol=1e-12)]
    assert len(top) == 41
    assert np.isclose(points[:, 0].max(), 50.0) and np.isclose(points[:, 1].min(), -50.0)


def test_a_patch_in_three_dimensions_bifurcates_at_the_exact_theorys_onset():
    # Vertical fibres (isotropic in the surface), a coarse patch one wavelength square: the two
    # shortest wave vectors are critical together (four negative pivots), within 1e-2 of the theory.
    r = fiberfold.pattern(fiberfold.Parameters(beta=1.5707963), elements_per_wavelength=3)
    assert r["negative_pivots"] == 4
    assert 0.0 < r["relative_difference"] < 1e-1
    assert {(w["m"], w["n"]) for w in r["mode_wave_vectors"][:2]} == {(1, 0), (0, 1)}
    with pytest.raises(ValueError, match="periods"):
        fiberfold.pattern(fiberfold.Parameters(), periods=0)


def test_a_patch_side_the_onset_mode_would_make_too_long_is_one_wavelength():
    # Fibres in the surface at 30 deg under d_3 = d / 2: the onset lies 1 deg from X, and Z would
    # take some sixty wavelengths. Capped, it holds the wave along X.
    p = fiberfold.Parameters(beta=0.0, psi=0.5235988)
    r = fiberfold.pattern(p, biaxial=0.5, elements_per_wavelength=3)
    (capped,) = r["capped_sides"]
    wavelength = 2 * np.pi / r["onset_theory"]["k0"]
    assert capped["side"] == "Z" and capped["period"] > 50 * wavelength
    assert np.isclose(r["patch"]["length_z"], wavelength)
    assert r["mode_wave_vectors"][0]["n"] == 0
    with pytest.raises(ValueError, match="max-side"):
        fiberfold.pattern(p, biaxial=0.5, max_side=0.5)


def test_the_pattern_past_the_onset_of_inclined_fibres_is_stripes_along_them():
    # One critical wave vector (at 120 deg for fibres at psi = 30 deg): the path past the onset
    # keeps it alone, growing from the seed, with no unstable branch to leave.
    p = fiberfold.Parameters(beta=0.785398, psi=0.5235988)
    r = fiberfold.pattern(p, elements_per_wavelength=3, follow_to=0.12)
    # Equibiaxial: the patch is built along the fibres' projection, 30 deg from X.
    assert abs(r["patch_azimuth_degrees"] - 30.0) < 1e-4
    path = r["path"]
    assert path["d_reached"] == 0.12 and path["stopped"] is None
    assert path["branches_left"] == []
    last = path["last"]
    assert last["pattern"] == "stripes" and last["negative_pivots"] == 0
    assert abs(last["directions"][0]["wave"]["theta_degrees"] - 120.0) < 0.5
    assert last["amplitude"] > 10 * path["imperfection"]
    with pytest.raises(ValueError, match="follow-to"):
        fiberfold.pattern(p, follow_to=0.99)


def test_a_pattern_path_asked_to_resume_without_a_checkpoint_starts_from_the_beginning(tmp_path):
    # Too short a path for a checkpoint (every 25 states): resume=True then runs it whole, the
    # same as without; without out it is refused.
    p = fiberfold.Parameters(beta=0.785398, psi=0.5235988)
    run = dict(elements_per_wavelength=3, follow_to=0.06, out=tmp_path / "patch")
    whole = fiberfold.pattern(p, **run)
    table = (tmp_path / "patch" / "pattern.csv").read_text()
    assert not (tmp_path / "patch" / "checkpoint.bin").exists()
    again = fiberfold.pattern(p, resume=True, **run)
    assert (tmp_path / "patch" / "pattern.csv").read_text() == table
    assert again["path"]["last"] == whole["path"]["last"]
    with pytest.raises(ValueError, match="out"):
        fiberfold.pattern(p, follow_to=0.08, resume=True)


def test_a_path_followed_past_the_onset_ends_that_far_past_the_theorys_onset():
    # Vertical fibres on a coarse patch: the path ends at the theory's d_c + 0.01.
    p = fiberfold.Parameters(beta=1.5707963)
    r = fiberfold.pattern(p, elements_per_wavelength=3, follow_past=0.01)
    assert abs(r["path"]["d_reached"] - (r["onset_theory"]["d_c"] + 0.01)) < 1e-9
    with pytest.raises(ValueError, match="follow_past"):
        fiberfold.pattern(p, follow_to=0.2, follow_past=0.01)
    with pytest.raises(ValueError, match="follow-past"):
        fiberfold.pattern(p, follow_past=0.9)
