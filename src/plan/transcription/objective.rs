//! The objective's residuals at a node (paper eq. 12 and section 5.1): `√W τ` for `½∫τᵀWτ dt`, and `L⁻¹τ`
//! for `½∫τᵀH⁻¹τ dt`.

use super::NodeWork;
use crate::dynamics::{rnea_derivatives::rnea_derivatives, Data};
use crate::spatial::Vec3;

/// The residual of `½ τᵀH⁻¹τ`: `r = L⁻¹τ` with `H = LLᵀ`. Its exact Jacobian needs `∂L/∂q`; instead we use
/// `J = L⁻¹ ∂τ − r (½ g)ᵀ / ‖r‖²` with `gₖ = yᵀ (∂H/∂qₖ) y`, `y = H⁻¹τ`, whose `Jᵀr = (∂τ)ᵀy − ½ g` is the
/// exact gradient of `½ τᵀH⁻¹τ` — so the solvers' stationarity test, and the optimum, are exact, and
/// `JᵀJ` stays a sound Gauss–Newton model. `g` costs one more derivative pass: `yᵀ(∂H/∂qₖ)y` is
/// `yᵀ ∂(H y)/∂qₖ`, the `∂τ/∂q` of inverse dynamics at `(q, 0, y)` without gravity.
pub(super) fn inverse_inertia_residual(model: &crate::Model, data: &mut Data, w: &mut NodeWork, nv: usize, nl: usize, jac: bool) {
    use nalgebra::{DMatrix, DVector};
    let h = if jac { data.M.clone() } else { crate::dynamics::crba::crba(model, data, &w.q).clone() };
    let Some(chol) = h.cholesky() else {
        // H is positive definite for every valid model; keep the values finite if rounding says otherwise.
        w.res.copy_from_slice(&w.tau);
        return;
    };
    let l = chol.l();
    let tau = DVector::from_column_slice(&w.tau);
    let r = l.solve_lower_triangular(&tau).expect("L is invertible");
    w.res.copy_from_slice(r.as_slice());
    if !jac {
        return;
    }
    let y = chol.solve(&tau);
    let zeros = vec![0.0; nv];
    rnea_derivatives(model, data, &w.q, &zeros, y.as_slice(), &Vec3::zeros(), None);
    let g = data.dtau_dq.transpose() * &y;
    let rr = r.norm_squared();
    let solve_rows = |src: &[f64], cols: usize, dst: &mut [f64], correct: bool| {
        // src is row-major nv × cols; dst = L⁻¹ src (− r ½gᵀ/‖r‖² for the q-derivatives).
        let m = DMatrix::from_row_slice(nv, cols, src);
        let mut x = l.solve_lower_triangular(&m).expect("L is invertible");
        if correct && rr > 0.0 {
            x -= &r * (g.transpose() * (0.5 / rr));
        }
        for i in 0..nv {
            for c in 0..cols {
                dst[i * cols + c] = x[(i, c)];
            }
        }
    };
    solve_rows(&w.dq, nv, &mut w.rdq, true);
    solve_rows(&w.dv, nv, &mut w.rdv, false);
    solve_rows(&w.da, nv, &mut w.rda, false);
    if nl > 0 {
        solve_rows(&w.dl, nl, &mut w.rdl, false);
    }
}
