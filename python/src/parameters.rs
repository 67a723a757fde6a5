//! `fiberfold.Parameters`: the library's parameters from Python keywords (flat keys, dotted law
//! keys, or a law table as a dict), converted to the TOML values a parameters file holds.

use crate::to_py;
use fiberfold::parameters::{is_boolean, Parameters, LAW_TABLES};
use fiberfold::Error;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt};
use std::path::PathBuf;

/// The material and geometric parameters of Table 1 (`fiberfold params`).
#[pyclass(module = "fiberfold", name = "Parameters")]
#[derive(Clone)]
pub(crate) struct PyParameters {
    pub(crate) inner: Parameters,
}

/// Sets `key` of `p` from a Python value: a number (not a bool) for the moduli, fractions,
/// angle and law constants, a bool for `tension_only` and `incompressible`, a string for a law
/// (`"layer.law": "ogden"`) or the load (`load="growth"`), a list of numbers for an N-term Ogden law, or a dict for a whole
/// law table (`layer={"law": "ogden", "alpha": -25}`).
fn set_parameter(p: &mut Parameters, key: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
    let is_bool = value.is_instance_of::<PyBool>();
    let is_number = (value.is_instance_of::<PyFloat>() || value.is_instance_of::<PyInt>()) && !is_bool;
    let is_list = value.is_instance_of::<pyo3::types::PyList>() || value.is_instance_of::<pyo3::types::PyTuple>();
    let (accepted, expected) = if is_boolean(key) {
        (is_bool, "a bool")
    } else if key.ends_with(".law") {
        (value.is_instance_of::<pyo3::types::PyString>(), "a law name (str)")
    } else if key == "load" {
        (value.is_instance_of::<pyo3::types::PyString>(), "a load name (str)")
    } else if LAW_TABLES.contains(&key) {
        (value.is_instance_of::<PyDict>(), "a dict of law constants")
    } else if key.ends_with(".mu") || key.ends_with(".alpha") {
        (is_number || is_list, "a number or a list of numbers")
    } else {
        (is_number, "a number (float or int)")
    };
    if !accepted {
        // Unknown names are a ValueError naming the known ones, whatever the value.
        if let Err(e @ Error::UnknownParameter { .. }) = p.clone().set_value(key, &toml::Value::Float(1.0)) {
            return Err(to_py(e));
        }
        return Err(PyTypeError::new_err(format!(
            "`{key}` must be {expected}, not {}",
            value.get_type().name()?
        )));
    }
    p.set_value(key, &toml_value(key, value)?).map_err(to_py)
}

/// A Python value as the TOML value a parameters file would hold.
fn toml_value(key: &str, value: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyFloat>() || value.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if let Ok(text) = value.extract::<String>() {
        return Ok(toml::Value::String(text));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in dict.iter() {
            let name: String = k.extract()?;
            table.insert(name.clone(), toml_value(&format!("{key}.{name}"), &v)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if let Ok(items) = value.extract::<Vec<Bound<'_, PyAny>>>() {
        return Ok(toml::Value::Array(
            items.iter().map(|v| toml_value(key, v)).collect::<PyResult<_>>()?,
        ));
    }
    Err(PyTypeError::new_err(format!(
        "`{key}` must be a number, bool, string, list or dict, not {}",
        value.get_type().name()?
    )))
}

/// A TOML value as Python.
fn py_value<'py>(py: Python<'py>, value: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        toml::Value::Boolean(b) => PyBool::new(py, *b).to_owned().into_any(),
        toml::Value::Float(x) => PyFloat::new(py, *x).into_any(),
        toml::Value::Integer(i) => PyFloat::new(py, *i as f64).into_any(),
        toml::Value::String(text) => text.into_pyobject(py)?.into_any(),
        toml::Value::Array(items) => {
            let list: Vec<Bound<'py, PyAny>> = items.iter().map(|v| py_value(py, v)).collect::<PyResult<_>>()?;
            pyo3::types::PyList::new(py, list)?.into_any()
        }
        other => other.to_string().into_pyobject(py)?.into_any(),
    })
}

#[pymethods]
impl PyParameters {
    #[new]
    #[pyo3(signature = (**overrides))]
    fn new(overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let mut inner = Parameters::default();
        if let Some(overrides) = overrides {
            for (key, value) in overrides.iter() {
                set_parameter(&mut inner, &key.extract::<String>()?, &value)?;
            }
        }
        inner.validate().map_err(to_py)?;
        Ok(PyParameters { inner })
    }

    #[staticmethod]
    fn from_toml(path: PathBuf) -> PyResult<Self> {
        let inner = Parameters::from_toml_file(&path).map_err(to_py)?;
        inner.validate().map_err(to_py)?;
        Ok(PyParameters { inner })
    }

    fn to_toml(&self) -> String {
        self.inner.to_toml()
    }

    /// A copy with some values replaced (validated).
    #[pyo3(signature = (**overrides))]
    fn replace(&self, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let mut inner = self.inner.clone();
        if let Some(overrides) = overrides {
            for (key, value) in overrides.iter() {
                set_parameter(&mut inner, &key.extract::<String>()?, &value)?;
            }
        }
        inner.validate().map_err(to_py)?;
        Ok(PyParameters { inner })
    }

    /// Every parameter: the flat keys, then each law table's `law` and constants as dotted
    /// keys (`"layer.alpha"`); `Parameters(**p.to_dict())` gives `p` back.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for (key, value) in self.inner.entries() {
            dict.set_item(key, py_value(py, &value)?)?;
        }
        Ok(dict)
    }

    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.inner.entries().into_iter().find(|(key, _)| key == name) {
            Some((_, value)) => py_value(py, &value),
            None => Err(pyo3::exceptions::PyAttributeError::new_err(format!(
                "Parameters has no attribute `{name}`"
            ))),
        }
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }

    fn __repr__(&self) -> String {
        let fields: Vec<String> = self
            .inner
            .entries()
            .into_iter()
            .map(|(key, value)| match value {
                toml::Value::Boolean(flag) => format!("{key}={}", if flag { "True" } else { "False" }),
                toml::Value::String(text) => format!("{key}='{text}'"),
                other => format!("{key}={other}"),
            })
            .collect();
        format!("Parameters({})", fields.join(", "))
    }
}
