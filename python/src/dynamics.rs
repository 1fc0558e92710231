//! `mintorque.Model`: a figure (URDF, figure file or built-in human) and its dynamics on NumPy arrays. Each
//! algorithm takes one state (1-D arrays of `nv`) or a batch (2-D arrays `n × nv`, one state per row) and
//! returns arrays of the same batch shape; the model's scratch (`Data`) is allocated once and reused.

use crate::error;
use mintorque::dynamics::{aba::aba, crba::crba, rnea::rnea, rnea_derivatives::rnea_derivatives, Data};
use mintorque::spatial::Vec3;
use numpy::ndarray::{Array2, Array3, ArrayViewD, Axis};
use numpy::{IntoPyArray, PyArrayDyn, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use std::path::PathBuf;

/// A figure and its dynamics.
#[pyclass(module = "mintorque")]
pub struct Model {
    pub(crate) model: mintorque::Model,
    data: Data,
}

/// A batch of states: `n` rows of `nv`, and whether the caller gave one state (1-D) or a batch (2-D).
struct Batch {
    rows: Vec<Array2<f64>>,
    n: usize,
    single: bool,
}

impl Batch {
    /// State `k` of input `i`: a row of a standard-layout `n × nv` array, contiguous.
    fn state(&self, i: usize, k: usize) -> &[f64] {
        self.rows[i].row(k).to_slice().expect("owned arrays are in standard layout")
    }
}

fn batch(arrays: &[(&str, &PyReadonlyArrayDyn<'_, f64>)], nv: usize) -> PyResult<Batch> {
    let first = arrays[0].1;
    let single = first.ndim() == 1;
    let n = if single { 1 } else { first.shape()[0] };
    let mut rows = Vec::with_capacity(arrays.len());
    for (name, a) in arrays {
        let view: ArrayViewD<f64> = a.as_array();
        let shape = view.shape().to_vec();
        let ok = if single { shape == [nv] } else { shape.len() == 2 && shape == [n, nv] };
        if !ok {
            let want = if single { format!("({nv},)") } else { format!("({n}, {nv})") };
            return Err(error(format!(
                "{name}: shape {shape:?}, expected {want} (one value per joint{})",
                if single { "" } else { ", one row per state" }
            )));
        }
        let owned = view.to_owned().into_shape_with_order((n, nv)).map_err(error)?;
        if owned.iter().any(|x| !x.is_finite()) {
            return Err(error(format!("{name}: holds a value that is not finite")));
        }
        rows.push(owned);
    }
    Ok(Batch { rows, n, single })
}

/// `n × nv` as the caller's shape: `(nv,)` for one state.
fn shaped(py: Python<'_>, out: Array2<f64>, single: bool) -> Bound<'_, PyArrayDyn<f64>> {
    let out = out.into_dyn();
    if single {
        out.index_axis_move(Axis(0), 0).into_pyarray(py)
    } else {
        out.into_pyarray(py)
    }
}

/// `n × nv × nv` as the caller's shape: `(nv, nv)` for one state.
fn shaped3(py: Python<'_>, out: Array3<f64>, single: bool) -> Bound<'_, PyArrayDyn<f64>> {
    let out = out.into_dyn();
    if single {
        out.index_axis_move(Axis(0), 0).into_pyarray(py)
    } else {
        out.into_pyarray(py)
    }
}

impl Model {
    fn new(model: mintorque::Model) -> Model {
        let data = Data::new(&model);
        Model { model, data }
    }

    /// `f` at every state of a batch of three arrays, one `nv`-vector per state, in the caller's shape.
    fn per_state<'py>(
        &mut self,
        py: Python<'py>,
        inputs: [(&str, &PyReadonlyArrayDyn<'py, f64>); 3],
        f: impl for<'d> Fn(&mintorque::Model, &'d mut Data, [&[f64]; 3]) -> &'d nalgebra::DVector<f64>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let nv = self.model.nv();
        let b = batch(&inputs, nv)?;
        let mut out = Array2::zeros((b.n, nv));
        for k in 0..b.n {
            let r = f(&self.model, &mut self.data, [b.state(0, k), b.state(1, k), b.state(2, k)]);
            out.row_mut(k).iter_mut().zip(r.iter()).for_each(|(o, v)| *o = *v);
        }
        Ok(shaped(py, out, b.single))
    }

    fn gravity(&self, gravity: Option<[f64; 3]>) -> PyResult<Vec3> {
        let g = gravity.map_or(self.model.gravity, |g| Vec3::new(g[0], g[1], g[2]));
        mintorque::dynamics::batch::check_gravity(&g, "gravity", "gravity").map_err(error)?;
        Ok(g)
    }
}

#[pymethods]
impl Model {
    /// Reads a URDF (`.urdf`) or figure file (`.toml`).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Model> {
        mintorque::model::load_any(&path).map(Model::new).map_err(error)
    }

    /// A built-in human: `structure` one of sagittal, free_arms, hanging, push_up; stature (m), mass (kg).
    #[staticmethod]
    #[pyo3(signature = (structure = "sagittal", stature = 1.83, mass = 81.0))]
    fn human(structure: &str, stature: f64, mass: f64) -> PyResult<Model> {
        use mintorque::model::human::{HumanParams, Structure};
        let s = Structure::from_name(structure).map_err(error)?;
        s.build(HumanParams { stature_m: stature, mass_kg: mass }).map(Model::new).map_err(error)
    }

    /// Degrees of freedom.
    #[getter]
    fn nv(&self) -> usize {
        self.model.nv()
    }

    /// The joints' names, in the order of every array.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.model.joint_names().iter().map(|s| s.to_string()).collect()
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> String {
        self.model.name.clone()
    }

    /// Inverse dynamics `τ = H(q)q̈ + C(q, q̇)` (N·m or N) under `gravity` (m/s², default the model's).
    #[pyo3(signature = (q, v, a, gravity = None))]
    fn rnea<'py>(
        &mut self,
        py: Python<'py>,
        q: PyReadonlyArrayDyn<'py, f64>,
        v: PyReadonlyArrayDyn<'py, f64>,
        a: PyReadonlyArrayDyn<'py, f64>,
        gravity: Option<[f64; 3]>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let g = self.gravity(gravity)?;
        self.per_state(py, [("q", &q), ("v", &v), ("a", &a)], |m, d, [q, v, a]| rnea(m, d, q, v, a, &g, None))
    }

    /// The derivatives of inverse dynamics: `(∂τ/∂q, ∂τ/∂q̇, H)`, each `nv × nv` per state.
    #[pyo3(signature = (q, v, a, gravity = None))]
    #[allow(clippy::type_complexity)]
    fn rnea_derivatives<'py>(
        &mut self,
        py: Python<'py>,
        q: PyReadonlyArrayDyn<'py, f64>,
        v: PyReadonlyArrayDyn<'py, f64>,
        a: PyReadonlyArrayDyn<'py, f64>,
        gravity: Option<[f64; 3]>,
    ) -> PyResult<(Bound<'py, PyArrayDyn<f64>>, Bound<'py, PyArrayDyn<f64>>, Bound<'py, PyArrayDyn<f64>>)> {
        let (nv, g) = (self.model.nv(), self.gravity(gravity)?);
        let b = batch(&[("q", &q), ("v", &v), ("a", &a)], nv)?;
        let mut out = [Array3::zeros((b.n, nv, nv)), Array3::zeros((b.n, nv, nv)), Array3::zeros((b.n, nv, nv))];
        for k in 0..b.n {
            rnea_derivatives(&self.model, &mut self.data, b.state(0, k), b.state(1, k), b.state(2, k), &g, None);
            for (o, m) in out.iter_mut().zip([&self.data.dtau_dq, &self.data.dtau_dv, &self.data.M]) {
                for r in 0..nv {
                    for c in 0..nv {
                        o[(k, r, c)] = m[(r, c)];
                    }
                }
            }
        }
        let [dq, dv, h] = out;
        Ok((shaped3(py, dq, b.single), shaped3(py, dv, b.single), shaped3(py, h, b.single)))
    }

    /// The joint-space inertia matrix `H(q)` (composite rigid body algorithm), `nv × nv` per state.
    fn crba<'py>(&mut self, py: Python<'py>, q: PyReadonlyArrayDyn<'py, f64>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let nv = self.model.nv();
        let b = batch(&[("q", &q)], nv)?;
        let mut out = Array3::zeros((b.n, nv, nv));
        for k in 0..b.n {
            let h = crba(&self.model, &mut self.data, b.state(0, k));
            for r in 0..nv {
                for c in 0..nv {
                    out[(k, r, c)] = h[(r, c)];
                }
            }
        }
        Ok(shaped3(py, out, b.single))
    }

    /// Forward dynamics `q̈ = H⁻¹(τ − C)` (articulated body algorithm) under `gravity` (m/s²).
    #[pyo3(signature = (q, v, tau, gravity = None))]
    fn aba<'py>(
        &mut self,
        py: Python<'py>,
        q: PyReadonlyArrayDyn<'py, f64>,
        v: PyReadonlyArrayDyn<'py, f64>,
        tau: PyReadonlyArrayDyn<'py, f64>,
        gravity: Option<[f64; 3]>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let g = self.gravity(gravity)?;
        self.per_state(py, [("q", &q), ("v", &v), ("tau", &tau)], |m, d, [q, v, t]| aba(m, d, q, v, t, &g, None))
    }

    fn __repr__(&self) -> String {
        format!("Model({:?}, nv={})", self.model.name, self.model.nv())
    }
}
