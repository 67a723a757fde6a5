"""fiberfold: wrinkling, creasing and folding of a stiff layer on a fibre-reinforced substrate.

The same Rust library as the ``fiberfold`` command line, with numpy arrays in and out. Names,
keys and units are the CLI's: lengths in units of the layer thickness H, moduli in units of the
substrate shear modulus mu_s, ``d = 1 - lambda_1`` the end-shortening, ``k`` the referential
wavenumber, ``beta`` the fibre angle in radians. ``phi_f`` weights *each* of the two fibre
families (eq. 3 of the paper).

Long calls (``simulate``, ``sweep``, ``bifurcation``, ``pattern``) release the GIL, accept a progress
callback, and stop on Ctrl-C with ``KeyboardInterrupt``. A solver failure raises
:class:`SolverError`; bad input raises ``ValueError`` (wrong value, naming the parameter and its
allowed range) or ``TypeError`` (wrong type).
"""

from __future__ import annotations

import json
import tempfile
import types
from typing import Any, Callable, Dict, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from ._fiberfold import Parameters, SolverError, State
from . import _fiberfold

__all__ = [
    "Parameters",
    "State",
    "SolverError",
    "Onset",
    "Simulation",
    "homogeneous",
    "dispersion",
    "onset",
    "sweep",
    "simulate",
    "simulate_defaults",
    "bifurcation",
    "pattern",
    "crease",
    "crease_defaults",
]

ArrayLike = Union[Sequence[float], np.ndarray, float]


def _check_parameters(params: Any) -> Parameters:
    if not isinstance(params, Parameters):
        raise TypeError(f"params must be fiberfold.Parameters, not {type(params).__name__}")
    return params


class Onset(types.SimpleNamespace):
    """The onset of wrinkling: the keys of ``onset.json`` as attributes (``load``, ``k0``,
    ``d_c`` (under growth the strain ``1 - 1/g_c``), ``g_c`` (the critical growth, None under
    compression), ``lambda1_c``, ``d_ellipticity_loss``, ``d_domain_end``, ``wavelength``, ``minimum``,
    ``biaxial``, ``theta0``, ``direction_spread``, ``method``, ``parameters``)."""

    def as_dict(self) -> Dict[str, Any]:
        return dict(vars(self))


def homogeneous(params: Parameters, d: ArrayLike) -> Dict[str, np.ndarray]:
    """The homogeneous state at each end-shortening ``d`` (each in [0, 1)): the columns of
    ``homogeneous.csv`` (``d``, ``lambda1``, ``lambda2_layer``, ``lambda2_substrate``,
    ``J_layer``, ``J_substrate``, Cauchy stresses ``sigma11/22/33_layer`` and ``_substrate`` in
    units of mu_s, and each layer's growth ``growth_layer``, ``growth_substrate``), each a
    float64 array of the length of ``d``. Under a growth load ``d`` is the strain ``1 - 1/g``."""
    return _fiberfold.homogeneous(_check_parameters(params), np.atleast_1d(np.asarray(d, dtype=float)))


def dispersion(
    params: Parameters,
    k: ArrayLike,
    method: str = "exact",
    biaxial: Optional[float] = None,
    theta: Optional[float] = None,
) -> Dict[str, np.ndarray]:
    """The critical compression ``d_c(k)`` of the linear theory at each wavenumber ``k > 0``:
    ``k``, ``d_c``, ``lambda1_c`` where a bifurcation exists, and ``k_without_root`` where none
    does before d = 0.95 or the loss of ellipticity. ``method``: ``"exact"`` (Stroh) or
    ``"discrete"`` (finite elements in Y). ``biaxial = R`` (``d_3 = R d``) or ``theta`` (the
    wave direction in the surface, radians from X) analyse waves in the surface with three
    displacement components (``theta`` 0 by default); both ``None`` is the paper's plane strain."""
    return _fiberfold.dispersion(
        _check_parameters(params), np.atleast_1d(np.asarray(k, dtype=float)), method, biaxial, theta
    )


def onset(
    params: Parameters, method: str = "exact", biaxial: Optional[float] = None, theta: Optional[float] = None
) -> Onset:
    """The onset of wrinkling: the minimum over k of ``d_c(k)`` (``k0``, ``d_c``, ``theta0``,
    ...). With ``biaxial = R`` (``d_3 = R d``) and no ``theta``, also the minimum over the wave
    directions of the surface: ``theta0`` (radians from X; ``None`` where none is preferred) and
    ``direction_spread``."""
    return Onset(**json.loads(_fiberfold.onset(_check_parameters(params), method, biaxial, theta)))


def sweep(
    params: Parameters,
    name: str,
    values: ArrayLike,
    series: Optional[Tuple[str, Sequence[float]]] = None,
    method: str = "exact",
    biaxial: Optional[float] = None,
    theta: Optional[float] = None,
) -> Dict[str, np.ndarray]:
    """The onset along ``values`` of the numeric parameter ``name`` (for each value of
    ``series = (other_name, [v1, v2, ...])`` if given): arrays ``series`` (NaN without a
    series), ``value``, ``k0``, ``d_c`` (NaN where no onset exists) and ``theta0``, as in
    ``sweep.csv``. ``biaxial`` and ``theta`` as in :func:`onset`. A swept shear modulus
    (``mu_l``, ``mu_s``) takes its bulk modulus along, keeping Poisson's ratio, as ``fiberfold
    sweep`` does."""
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, not {type(name).__name__}")
    if series is not None:
        key, levels = series
        series = (str(key), [float(v) for v in levels])
    return _fiberfold.sweep(
        _check_parameters(params), name, np.atleast_1d(np.asarray(values, dtype=float)), series, method, biaxial, theta
    )


class Simulation:
    """A finite-element run (``fiberfold simulate``) kept in memory.

    Attributes:
        amplitude: the columns of ``amplitude.csv`` (``d``, ``A``, ``strain_energy``,
            ``newton_iterations``, ``residual``, ``min_J``, ``step_seconds``, ``in_contact``,
            ``contact_length``, ``penetration``, ``stabilisation_energy_fraction``, ``snap``, ``minimised``,
            ``ellipticity_layer``, ``ellipticity_substrate``, ``growth_layer``), one float64
            array each, one entry per accepted state.
        summary: the content of ``simulate.json`` (its ``files`` empty: nothing is written);
            each of its keys is also an attribute:
        onset: the content of ``onset_estimates.json`` (the three estimates and the linear theory).
        contact: the content of ``contact.json``.
        secondary: the content of ``secondary.json``: ``d_secondary``, every change of the
            tangent's inertia (``changes``: ``d_before``, ``d_after``, ``negative_before``,
            ``negative_after``, and for the first few the ``eigenvalue`` and
            ``mode_half_waves`` of their mode) and the ``branch`` the run ended on.
        snaps, ellipticity, mesh, k, imperfection, d_max, d_reached, completed, accepted_steps,
            cuts, totals, wall_seconds, parameters, load, g_reached: the other keys of
            ``simulate.json``.
        unknowns, element: the mesh's number of unknowns and its element (``"displacement"`` or
            ``"mixed"``), from ``mesh``.
        state: the last converged state (:class:`State`: reference ``points``,
            ``deformed_points``, ``cells``, ``point_data``, ``cell_data``, ``write_vtu(path)``),
            ready for pyvista or meshio.
        stopped: why the path ended before ``d_max`` (None if it did not).
    """

    def __init__(self, columns: Dict[str, np.ndarray], summary: Dict[str, Any], state: State, stopped: Optional[str]):
        self.amplitude = columns
        self.state = state
        self.stopped = stopped
        self.summary = summary
        for key, value in summary.items():
            setattr(self, key, value)
        self.unknowns = summary["mesh"]["unknowns"]
        self.element = summary["mesh"]["element"]

    def to_meshio(self) -> Any:
        """The last state as a ``meshio.Mesh`` (needs meshio): cells of type ``quad9``."""
        import meshio  # optional dependency

        cell_data = {name: [values] for name, values in self.state.cell_data.items()}
        return meshio.Mesh(
            self.state.points,
            [("quad9", self.state.cells)],
            point_data=dict(self.state.point_data),
            cell_data=cell_data,
        )

    def __repr__(self) -> str:
        return (
            f"Simulation(d_reached={self.d_reached}, accepted_steps={self.accepted_steps}, "
            f"completed={self.completed}, unknowns={self.unknowns})"
        )


def simulate(
    params: Parameters,
    waves: Optional[float] = None,
    *,
    progress: Optional[Callable[[Dict[str, Any]], None]] = None,
    out: Optional[str] = None,
    **options: Any,
) -> Simulation:
    """The paper's finite-element protocol, exactly as ``fiberfold simulate``, with the same
    options by the same names: :func:`simulate_defaults` gives every one with its default (the
    CLI's; see ``fiberfold simulate --help`` for each).

    ``waves`` is the number N of seeded waves across the half domain (2N an integer), or give
    ``k = m pi / 50``. ``mesh`` is ``"coarse"``, ``"fine"`` or ``"extra"``, modified by ``nx``,
    ``layer_elements``, ``substrate_elements`` and ``h0`` (or ``grading``). ``element`` is
    ``"mixed"`` (the default, as ``fiberfold simulate``'s: more accurate, and needed for nearly
    and exactly incompressible tissue) or ``"displacement"`` (the paper's). ``stabilisation`` is how a snap is crossed: ``"viscous"`` (damped
    steps, with ``eta``), ``"snap"`` (the energy is minimised at that d and the stable
    equilibrium reached is recorded, see ``summary["snaps"]``; the inertia of every state is then
    counted, whatever ``inertia`` says) or ``"none"``. ``continuation`` is how the path is
    followed: ``"displacement"`` control (the default) or ``"arc-length"``, which goes round a
    limit point in d along the unstable branch (with ``contact=False, stabilisation="none"``;
    ``d`` then falls and rises again). ``progress`` is
    called with a dict (``event``: ``"stage"``, ``"step"`` or ``"cut"``; ``d``, ``A``,
    ``message``...) after every stage, accepted state and cut. With ``out``, the run also
    writes the command's files into that folder, with its checkpoints (``checkpoint_every``,
    ``checkpoint_seconds``); ``resume=True`` then continues from the checkpoint there, as
    ``fiberfold simulate --resume`` does (from the beginning if there is none). An unknown option raises
    ``ValueError``, a value of the wrong type ``TypeError``. Raises :class:`SolverError` (with
    ``result``, the path so far) if the path stops before ``d_max``.
    """
    if progress is not None and not callable(progress):
        raise TypeError("progress must be callable")
    if waves is not None:
        options["waves"] = waves
    if options.get("resume") and out is None:
        raise ValueError("resume=True continues the checkpoint of a folder: give out")
    keywords = json.dumps(options, default=_plain)
    folder = None if out is None else str(out)
    columns, summary, state, stopped = _fiberfold.simulate_run(_check_parameters(params), keywords, progress, folder)
    result = Simulation(columns, json.loads(summary), state, stopped)
    if stopped is not None:
        error = SolverError(f"{stopped}; the path up to d = {result.d_reached:.6f} is in the exception's `result`")
        error.result = result
        raise error
    return result


def simulate_defaults() -> Dict[str, Any]:
    """Every option of :func:`simulate` with its default (those of ``fiberfold simulate``)."""
    return dict(json.loads(_fiberfold.simulate_defaults()))


def _plain(value: Any) -> Any:
    """A NumPy scalar as the Python number JSON takes."""
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"{value!r} is not a number, a string or a boolean")


def bifurcation(
    params: Parameters, mesh: str = "coarse", out: Optional[str] = None, element: Optional[str] = None
) -> Dict[str, Any]:
    """The exact bifurcation of the discretised perfect system (``fiberfold bifurcation``):
    the content of ``bifurcation.json`` (``d_bifurcation``, ``k_mode``, the linear theory's
    minimum, ...). Its files (mode VTU and figure) go to ``out``, or to a temporary folder that
    is removed. ``element``: ``"mixed"`` (None: the default, as ``fiberfold bifurcation``'s) or
    ``"displacement"``."""
    params = _check_parameters(params)
    if out is not None:
        return json.loads(_fiberfold.bifurcation_run(params, str(out), mesh, element))
    with tempfile.TemporaryDirectory() as folder:
        return json.loads(_fiberfold.bifurcation_run(params, folder, mesh, element))


def pattern(
    params: Parameters,
    biaxial: float = 1.0,
    periods: int = 1,
    elements_per_wavelength: int = 6,
    follow_to: Optional[float] = None,
    imperfection: float = 0.01,
    out: Optional[str] = None,
    follow_past: Optional[float] = None,
    resume: bool = False,
    max_side: float = 4.0,
) -> Dict[str, Any]:
    """A patch of tissue in three dimensions under ``d_3 = biaxial * d`` (``fiberfold
    pattern``): the content of ``pattern.json`` (``d_bifurcation``, ``negative_pivots``, the
    theory's ``d_c_admissible`` over the patch's wave vectors, ``mode_wave_vectors``, the
    ``patch``, ...); under an equal load (``biaxial=1``, no prestrain) the patch is built along
    the fibres' projection, ``patch_azimuth_degrees`` from X, and every angle is from X. With
    ``follow_to``, the path past the onset is followed to that ``d``
    (with ``follow_past`` instead, to the theory's onset ``d_c`` plus it), seeded with every
    critical wave of amplitude ``imperfection``: ``path`` then holds its summary (the pattern's
    ``changes``, the ``last`` state) and ``pattern.csv`` one row per state. Its files (VTU,
    spectra, top views) go to ``out``, or to a temporary folder that is removed. The path writes
    checkpoints into ``out``; ``resume=True`` continues it from the last one there, as
    ``fiberfold pattern --resume`` does. A side along which the onset mode's period exceeds
    ``max_side`` wavelengths is one wavelength per period (``capped_sides``), as
    ``--max-side`` says."""
    params = _check_parameters(params)
    if resume and out is None:
        raise ValueError("resume=True continues the checkpoint of a folder: give out")
    arguments = (biaxial, periods, elements_per_wavelength, follow_to, imperfection, follow_past, resume, max_side)
    if out is not None:
        return json.loads(_fiberfold.pattern_run(params, str(out), *arguments))
    with tempfile.TemporaryDirectory() as folder:
        return json.loads(_fiberfold.pattern_run(params, folder, *arguments))


def crease(
    params: Parameters,
    folds: Optional[Sequence[float]] = None,
    **options: Any,
) -> Dict[str, Any]:
    """The crease onset (``fiberfold crease``): where a seeded crease of reference length ``a``
    (each of ``folds``, units of H) first lowers the energy below the flat state's (Hong, Zhao
    and Suo's criterion). The options are the CLI's flags by name (``d_from``, ``d_to``,
    ``d_step``, ``tolerance``, ``size``, ``nx``, ``layer_elements``, ``substrate_elements``,
    ``ratio``, ``layer_grading``, ``element``, ``criterion``, ``convergence``,
    ``mesh_tolerance``, ``max_meshes``, ``every_fold``, ``beyond_wrinkle``);
    :func:`crease_defaults` gives each with its default. The scan ends 0.01 past the wrinkling
    onset of the linear theory (``beyond_wrinkle=True`` scans on to ``d_to``) and only the
    lowest threshold is located and refined (``every_fold=True`` converges each fold's).
    ``criterion="released"`` compares the equilibrium crease the fold closes to once released
    to frictionless contact (``"held"``, the default: the fold held on the plane). Each threshold is
    computed on the base mesh with its element counts times 1, 2, 3, ... (at most
    ``max_meshes``) until it changes by less than ``mesh_tolerance`` in d, and extrapolated with
    the observed order (``convergence=False``: the base mesh alone). The content of
    ``crease.json``: ``d_crease`` (the smallest extrapolated threshold, None if none within the
    scan), ``d_crease_error`` (its uncertainty), ``order``, ``converged``, ``fold_length``,
    ``depth``, ``meshes``, ``d_wrinkle`` and ``first`` (which comes first: ``"wrinkle"``,
    ``"crease"``, ``"too_close_to_call"``, ``"undecided"`` or ``"none"``), and every fold's
    ``thresholds`` per mesh, ``extrapolated`` and energies. An unknown option raises ``ValueError``, a value of the wrong type ``TypeError``."""
    if folds is not None:
        options["folds"] = [float(a) for a in folds]
    keywords = json.dumps(options, default=_plain)
    return json.loads(_fiberfold.crease_run(_check_parameters(params), keywords))


def crease_defaults() -> Dict[str, Any]:
    """Every option of :func:`crease` with its default (those of ``fiberfold crease``)."""
    return dict(json.loads(_fiberfold.crease_defaults()))
