//! `fiberfold._fiberfold`: the Python face of the fiberfold library. Every function calls the
//! library as the CLI does (same names, keys, units and defaults); nothing is computed here.
//! Long calls release the GIL, report to an optional progress callback and stop within a step
//! on Ctrl-C (`KeyboardInterrupt`). The public, typed API is `fiberfold/__init__.py`.

use fiberfold::output::vtu::DataArray;
use fiberfold::stability::Method;
use fiberfold::studies::homogeneous::{table, CSV_HEADER};
use fiberfold::studies::orientation::Modes;
use fiberfold::studies::simulate::{
    self, amplitude_header, amplitude_row, Progress, SimulateOptions, SimulationSummary, StateFields,
};
use fiberfold::studies::stability::{check_wavenumbers, DispersionCurve, OnsetSummary, Solver, SweepStudy};
use fiberfold::Error;
use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArrayLike1};
use pyo3::create_exception;
use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::sync::Mutex;

mod parameters;

use parameters::PyParameters;

create_exception!(
    _fiberfold,
    SolverError,
    PyRuntimeError,
    "A nonlinear solve or a load path that failed; `result` holds what was computed before."
);

/// A library error as the matching Python exception (bad input: `ValueError`).
fn to_py(error: Error) -> PyErr {
    match error {
        e @ Error::WrongType { .. } => PyTypeError::new_err(e.to_string()),
        e if e.is_user_input() => PyValueError::new_err(e.to_string()),
        Error::Interrupted(m) => PyKeyboardInterrupt::new_err(m),
        e @ Error::Io { .. } => PyOSError::new_err(e.to_string()),
        e => SolverError::new_err(e.to_string()),
    }
}

fn method(name: &str) -> PyResult<Method> {
    Solver::from_name(name).map(Solver::method).map_err(to_py)
}

/// The homogeneous state at each `d`: the columns of `homogeneous.csv`.
#[pyfunction]
fn homogeneous<'py>(
    py: Python<'py>,
    params: &PyParameters,
    d: PyArrayLike1<'py, f64, AllowTypeChange>,
) -> PyResult<Bound<'py, PyDict>> {
    let ds = d.as_array().to_vec();
    let p = params.inner.clone();
    let rows = py.detach(|| table(&p, &ds)).map_err(to_py)?;
    let dict = PyDict::new(py);
    for (c, name) in CSV_HEADER.iter().enumerate() {
        let column: Vec<f64> = rows.iter().map(|r| r[c]).collect();
        dict.set_item(*name, column.into_pyarray(py))?;
    }
    Ok(dict)
}

/// `d_c(k)` at each `k` (continued from one to the next): `k`, `d_c`, `lambda1_c` where a root
/// exists, and `k_without_root`, as in `dispersion.csv` / `dispersion.json`.
#[pyfunction]
#[pyo3(signature = (params, k, method_name = "exact", biaxial = None, theta = None))]
fn dispersion<'py>(
    py: Python<'py>,
    params: &PyParameters,
    k: PyArrayLike1<'py, f64, AllowTypeChange>,
    method_name: &str,
    biaxial: Option<f64>,
    theta: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let ks = k.as_array().to_vec();
    check_wavenumbers(&ks).map_err(to_py)?;
    let method = method(method_name)?;
    let p = params.inner.clone();
    let curve = py
        .detach(|| {
            let analysis = Modes { biaxial, theta }.analysis(&p, method)?;
            DispersionCurve::compute(&analysis, &ks, &|| {})
        })
        .map_err(to_py)?;
    let dict = PyDict::new(py);
    let (k, d): (Vec<f64>, Vec<f64>) = curve.points.iter().copied().unzip();
    let lambda: Vec<f64> = d.iter().map(|d| 1.0 - d).collect();
    dict.set_item("k", k.into_pyarray(py))?;
    dict.set_item("d_c", d.into_pyarray(py))?;
    dict.set_item("lambda1_c", lambda.into_pyarray(py))?;
    dict.set_item("k_without_root", curve.no_root.into_pyarray(py))?;
    Ok(dict)
}

/// The onset: the content of `onset.json`, as JSON text.
#[pyfunction]
#[pyo3(signature = (params, method_name = "exact", biaxial = None, theta = None))]
fn onset(
    py: Python<'_>,
    params: &PyParameters,
    method_name: &str,
    biaxial: Option<f64>,
    theta: Option<f64>,
) -> PyResult<String> {
    let method = method(method_name)?;
    let p = params.inner.clone();
    let summary = py
        .detach(|| OnsetSummary::new(&p, method, &Modes { biaxial, theta }))
        .map_err(to_py)?;
    serde_json::to_string(&summary).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// The onset along `values` of `name` (and for each value of `series`): `series`, `value`,
/// `k0`, `d_c` (NaN where no onset exists) and `theta0`, as in `sweep.csv`.
#[pyfunction]
#[pyo3(signature = (params, name, values, series = None, method_name = "exact", biaxial = None, theta = None))]
#[allow(clippy::too_many_arguments)]
fn sweep<'py>(
    py: Python<'py>,
    params: &PyParameters,
    name: String,
    values: PyArrayLike1<'py, f64, AllowTypeChange>,
    series: Option<(String, Vec<f64>)>,
    method_name: &str,
    biaxial: Option<f64>,
    theta: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let study = SweepStudy {
        param: name,
        from: 0.0,
        to: 0.0,
        points: 0,
        series,
        values: Some(values.as_array().to_vec()),
        method: method(method_name)?,
        modes: Modes { biaxial, theta },
        keep_poisson: true,
    };
    let p = params.inner.clone();
    let points = py.detach(|| study.compute(&p, &|| {})).map_err(to_py)?;
    let pick =
        |f: &dyn Fn(&fiberfold::studies::stability::SweepPoint) -> f64| -> Vec<f64> { points.iter().map(f).collect() };
    let dict = PyDict::new(py);
    dict.set_item("series", pick(&|p| p.series.unwrap_or(f64::NAN)).into_pyarray(py))?;
    dict.set_item("value", pick(&|p| p.value).into_pyarray(py))?;
    dict.set_item("k0", pick(&|p| p.onset.map_or(f64::NAN, |o| o.k0)).into_pyarray(py))?;
    dict.set_item("d_c", pick(&|p| p.onset.map_or(f64::NAN, |o| o.d_c)).into_pyarray(py))?;
    dict.set_item("theta0", pick(&|p| p.theta0).into_pyarray(py))?;
    Ok(dict)
}

/// The last state of a run: reference points (z = 0), VTK-ordered 9-node cells, point and
/// cell fields, as numpy arrays; `write_vtu` writes it as the CLI's snapshots.
#[pyclass(module = "fiberfold", name = "State")]
struct PyState {
    fields: StateFields,
}

#[pymethods]
impl PyState {
    /// `(n, 3)` reference coordinates (z = 0).
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<f64>> {
        let flat: Vec<f64> = self.fields.points.iter().flat_map(|&[x, y]| [x, y, 0.0]).collect();
        Array2::from_shape_vec((self.fields.points.len(), 3), flat)
            .expect("3 per point")
            .into_pyarray(py)
    }

    /// `(n, 3)` deformed coordinates: `points` plus the displacement.
    #[getter]
    fn deformed_points<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<f64>> {
        let f = &self.fields;
        let flat: Vec<f64> = f
            .points
            .iter()
            .zip(&f.displacement)
            .flat_map(|(&[x, y], &[ux, uy])| [x + ux, y + uy, 0.0])
            .collect();
        Array2::from_shape_vec((f.points.len(), 3), flat)
            .expect("3 per point")
            .into_pyarray(py)
    }

    /// `(m, 9)` node indices per cell, in VTK's order for `VTK_BIQUADRATIC_QUAD` (type 28).
    #[getter]
    fn cells<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<i64>> {
        let flat: Vec<i64> = self
            .fields
            .vtk_cells()
            .iter()
            .flat_map(|c| c.map(|n| n as i64))
            .collect();
        Array2::from_shape_vec((self.fields.cells.len(), 9), flat)
            .expect("9 per cell")
            .into_pyarray(py)
    }

    /// `{"displacement": (n, 3)}`.
    #[getter]
    fn point_data<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for array in self.fields.point_arrays() {
            dict.set_item(&array.name, shaped(py, &array))?;
        }
        Ok(dict)
    }

    /// `J`, `cauchy_stress` (6 components: XX, YY, ZZ, XY, YZ, XZ), `von_mises`,
    /// `fibre_stretch_1`, `fibre_stretch_2`, `layer` at the element centres.
    #[getter]
    fn cell_data<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for array in self.fields.cell_arrays() {
            dict.set_item(&array.name, shaped(py, &array))?;
        }
        Ok(dict)
    }

    /// Writes the state as a `.vtu` file (the CLI's snapshot format).
    fn write_vtu(&self, path: PathBuf) -> PyResult<()> {
        self.fields.write_vtu(&path).map_err(to_py)
    }
}

/// A data array as a numpy array: `(n,)` for scalars, `(n, components)` otherwise.
fn shaped<'py>(py: Python<'py>, array: &DataArray) -> Bound<'py, PyAny> {
    if array.components == 1 {
        array.values.clone().into_pyarray(py).into_any()
    } else {
        let rows = array.values.len() / array.components;
        Array2::from_shape_vec((rows, array.components), array.values.clone())
            .expect("whole entities")
            .into_pyarray(py)
            .into_any()
    }
}

/// Runs `simulate` with `options`, a JSON object of `fiberfold simulate`'s options (the
/// library's names; the missing ones at its defaults, [`simulate_defaults`]): in memory, or
/// writing its files (and checkpoints, from which `resume` continues) into `out`. Returns
/// `(columns, summary_json, state, stopped)`: the `amplitude.csv` columns as arrays, the JSON
/// text of `simulate.json` (with no files in memory), the last state, and why the path stopped
/// early (None if it reached `d_max`).
#[pyfunction]
#[pyo3(signature = (params, options, progress, out=None))]
fn simulate_run<'py>(
    py: Python<'py>,
    params: &PyParameters,
    options: &str,
    progress: Option<Py<PyAny>>,
    out: Option<PathBuf>,
) -> PyResult<(Bound<'py, PyDict>, String, PyState, Option<String>)> {
    let options = SimulateOptions::from_keywords(options).map_err(to_py)?;
    let study = options.study().map_err(to_py)?;
    let p = params.inner.clone();
    // The callback's or Ctrl-C's exception, raised once the library has stopped.
    let raised: Mutex<Option<PyErr>> = Mutex::new(None);
    let monitor = |event: Progress<'_>| -> fiberfold::Result<()> {
        Python::attach(|py| {
            let result = (|| -> PyResult<()> {
                if let Some(callback) = &progress {
                    let info = PyDict::new(py);
                    match event {
                        Progress::Stage(text) => {
                            info.set_item("event", "stage")?;
                            info.set_item("message", text)?;
                        }
                        Progress::Step(r) => {
                            info.set_item("event", "step")?;
                            info.set_item("d", r.d)?;
                            info.set_item("A", r.amplitude)?;
                            info.set_item("newton_iterations", r.iterations)?;
                        }
                        Progress::Cut(c) => {
                            info.set_item("event", "cut")?;
                            info.set_item("d", c.d)?;
                            info.set_item("message", &c.reason)?;
                        }
                    }
                    callback.call1(py, (info,))?;
                }
                py.check_signals()
            })();
            result.map_err(|e| {
                let message = e.to_string();
                *raised.lock().expect("not poisoned") = Some(e);
                Error::Interrupted(message)
            })
        })
    };
    let start = std::time::Instant::now();
    let solved = py.detach(|| match &out {
        Some(out) => {
            simulate::run_keeping(&p, &study, out, &monitor).map(|(summary, solution)| (Some(summary), solution))
        }
        None => simulate::solve(&p, &study, &monitor).map(|solution| (None, solution)),
    });
    if let Some(e) = raised.lock().expect("not poisoned").take() {
        return Err(e);
    }
    let (written, solution) = solved.map_err(to_py)?;
    let header = amplitude_header();
    let rows: Vec<Vec<f64>> = solution.curve.records.iter().map(amplitude_row).collect();
    let columns = PyDict::new(py);
    for (c, name) in header.iter().enumerate() {
        let column: Vec<f64> = rows.iter().map(|r| r[c]).collect();
        columns.set_item(*name, column.into_pyarray(py))?;
    }
    // The summary of `simulate.json`, without files when in memory.
    let summary = written
        .unwrap_or_else(|| SimulationSummary::new(&p, &study, &solution, Vec::new(), start.elapsed().as_secs_f64()));
    let summary = serde_json::to_string(&summary).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let stopped = solution.curve.stopped.as_ref().map(|e| e.to_string());
    Ok((columns, summary, PyState { fields: solution.state }, stopped))
}

/// Every option of `simulate` with its default, as a JSON object (the same as the CLI's).
#[pyfunction]
fn simulate_defaults() -> String {
    SimulateOptions::default_keywords()
}

/// The exact bifurcation of the discretised perfect system (`fiberfold bifurcation`), written
/// into `out`; returns `bifurcation.json` as JSON text.
#[pyfunction]
#[pyo3(signature = (params, out, mesh = "coarse", element = None))]
fn bifurcation_run(
    py: Python<'_>,
    params: &PyParameters,
    out: PathBuf,
    mesh: &str,
    element: Option<&str>,
) -> PyResult<String> {
    use fiberfold::studies::bifurcation::{run, BifurcationStudy};
    let study = BifurcationStudy::on_preset(mesh, element).map_err(to_py)?;
    let p = params.inner.clone();
    let report = py.detach(|| run(&p, &study, &out)).map_err(to_py)?;
    serde_json::to_string(&report).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// A patch of tissue in three dimensions (`fiberfold pattern`), written into `out`; returns
/// `pattern.json` as JSON text. The path is followed to `follow_to`, or to the theory's onset
/// plus `follow_past` (not both), from the checkpoint in `out` if `resume`.
#[pyfunction]
#[pyo3(signature = (params, out, biaxial=1.0, periods=1, elements_per_wavelength=6, follow_to=None, imperfection=0.01, follow_past=None, resume=false, max_side=4.0))]
#[allow(clippy::too_many_arguments)]
fn pattern_run(
    py: Python<'_>,
    params: &PyParameters,
    out: PathBuf,
    biaxial: f64,
    periods: usize,
    elements_per_wavelength: usize,
    follow_to: Option<f64>,
    imperfection: f64,
    follow_past: Option<f64>,
    resume: bool,
    max_side: f64,
) -> PyResult<String> {
    use fiberfold::studies::pattern::{run, PathEnd, PathStudy, PatternStudy};
    let end = match (follow_to, follow_past) {
        (Some(_), Some(_)) => {
            return Err(to_py(fiberfold::Error::invalid(
                "follow_past",
                "given with follow_to",
                "one of follow_to and follow_past",
            )))
        }
        (Some(d_end), None) => Some(PathEnd::At(d_end)),
        (None, Some(past)) => Some(PathEnd::PastOnset(past)),
        (None, None) => None,
    };
    let study = PatternStudy {
        biaxial,
        periods,
        elements_per_wavelength,
        max_side,
        path: end.map(|end| PathStudy {
            imperfection,
            end,
            ..PathStudy::default()
        }),
        resume,
        ..PatternStudy::default()
    };
    let p = params.inner.clone();
    let report = py.detach(|| run(&p, &study, &out, &mut |_| {})).map_err(to_py)?;
    serde_json::to_string(&report).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// The crease onset (`fiberfold crease`), in memory, with `options`, a JSON object of its
/// options by the library's names (the missing ones at its defaults, [`crease_defaults`]):
/// `crease.json` as JSON text.
#[pyfunction]
fn crease_run(py: Python<'_>, params: &PyParameters, options: &str) -> PyResult<String> {
    use fiberfold::studies::crease::{crease, CreaseOptions};
    let study = CreaseOptions::from_keywords(options)
        .and_then(|o| o.study())
        .map_err(to_py)?;
    let p = params.inner.clone();
    let report = py.detach(|| crease(&p, &study, &|| {})).map_err(to_py)?;
    serde_json::to_string(&report).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// Every option of `crease` with its default, as a JSON object (the same as the CLI's).
#[pyfunction]
fn crease_defaults() -> String {
    fiberfold::studies::crease::CreaseOptions::default_keywords()
}

/// The native module.
#[pymodule]
fn _fiberfold(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyParameters>()?;
    m.add_class::<PyState>()?;
    m.add("SolverError", m.py().get_type::<SolverError>())?;
    m.add_function(wrap_pyfunction!(homogeneous, m)?)?;
    m.add_function(wrap_pyfunction!(dispersion, m)?)?;
    m.add_function(wrap_pyfunction!(onset, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_run, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(bifurcation_run, m)?)?;
    m.add_function(wrap_pyfunction!(pattern_run, m)?)?;
    m.add_function(wrap_pyfunction!(crease_run, m)?)?;
    m.add_function(wrap_pyfunction!(crease_defaults, m)?)?;
    Ok(())
}
