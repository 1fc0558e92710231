//! Checks that a built model is a well-formed tree of physically possible bodies. Every loader
//! (URDF, figure file, built-in figures) calls [`Model::validate`] before handing a model out.

use super::{JointKind, Model};
use crate::error::{Error, Result};
use crate::spatial::Inertia;
use std::collections::HashSet;

impl Model {
    /// `origin` names the file or built-in the model came from, for the error message.
    pub fn validate(&self, origin: &str) -> Result<()> {
        let err = |element: String, message: String| Err(Error::model(origin, element, message));
        if self.joints.len() != self.bodies.len() {
            return err("model".into(), "joints and bodies differ in number".into());
        }
        let mut names = HashSet::new();
        for (i, j) in self.joints.iter().enumerate().skip(1) {
            let element = format!("joint \"{}\"", j.name);
            if !names.insert(j.name.as_str()) {
                return err(element, "duplicate joint name".into());
            }
            if j.kind == JointKind::Root {
                return err(element, "only joint 0 may be the root".into());
            }
            if j.parent >= i {
                return err(element, format!("its parent body {} does not come before it (a cycle or a broken tree)", j.parent));
            }
            let n = j.axis.norm();
            if !n.is_finite() || (n - 1.0).abs() > 1e-9 {
                return err(element, format!("axis must be a unit vector, got {:?}", j.axis.as_slice()));
            }
            let p = &j.placement;
            if !p.rotation.iter().chain(p.translation.iter()).all(|x| x.is_finite()) {
                return err(element, "origin is not finite (NaN or infinity)".into());
            }
            if (p.rotation.transpose() * p.rotation - crate::spatial::Mat3::identity()).norm() > 1e-9 {
                return err(element, "origin rotation is not a rotation matrix".into());
            }
            let l = &j.limits;
            if l.lower.is_nan() || l.upper.is_nan() || l.lower > l.upper {
                return err(element, format!("limits must satisfy lower ≤ upper, got [{}, {}]", l.lower, l.upper));
            }
            if l.velocity.is_nan() || l.velocity < 0.0 || l.effort.is_nan() || l.effort < 0.0 {
                return err(element, "velocity and effort limits must be ≥ 0".into());
            }
            let s = &j.passive;
            if !(s.stiffness.is_finite() && s.rest.is_finite() && s.damping.is_finite()) || s.stiffness < 0.0 || s.damping < 0.0 {
                return err(element, "spring stiffness and damping must be finite and ≥ 0".into());
            }
        }
        let mut body_names = HashSet::new();
        for b in &self.bodies {
            if !body_names.insert(b.name.as_str()) {
                return err(format!("link \"{}\"", b.name), "duplicate link name".into());
            }
            check_inertia(&b.inertia).or_else(|m| err(format!("link \"{}\" inertia", b.name), m))?;
        }
        let mut frame_names = HashSet::new();
        for f in &self.frames {
            if !frame_names.insert(f.name.as_str()) {
                return err(format!("frame \"{}\"", f.name), "duplicate frame name".into());
            }
            if f.body >= self.bodies.len() {
                return err(format!("frame \"{}\"", f.name), "attached to a body that does not exist".into());
            }
        }
        // Every degree of freedom must move some mass, or H(q) is singular.
        let mut subtree_mass: Vec<f64> = self.bodies.iter().map(|b| b.inertia.mass).collect();
        for i in (1..self.bodies.len()).rev() {
            let p = self.joints[i].parent;
            subtree_mass[p] += subtree_mass[i];
        }
        for i in 1..self.bodies.len() {
            if subtree_mass[i] <= 0.0 {
                return err(
                    format!("joint \"{}\"", self.joints[i].name),
                    "moves no mass: the joint-space inertia matrix would be singular".into(),
                );
            }
        }
        if !self.gravity.iter().all(|x| x.is_finite()) {
            return err("gravity".into(), "not finite".into());
        }
        Ok(())
    }
}

/// A physically possible rigid body: mass ≥ 0, inertia symmetric positive semi-definite with principal
/// moments obeying the triangle inequality (`I₁ + I₂ ≥ I₃`), everything finite.
pub fn check_inertia(i: &Inertia) -> std::result::Result<(), String> {
    if !i.mass.is_finite() || !i.com.iter().all(|x| x.is_finite()) || !i.inertia_com.iter().all(|x| x.is_finite()) {
        return Err("not finite (NaN or infinity)".into());
    }
    if i.mass < 0.0 {
        return Err(format!("mass must be ≥ 0, got {} kg", i.mass));
    }
    let m = &i.inertia_com;
    let scale = m.norm().max(1e-300);
    if (m - m.transpose()).norm() > 1e-9 * scale {
        return Err("inertia matrix is not symmetric".into());
    }
    if i.mass == 0.0 {
        if m.norm() > 0.0 {
            return Err("a massless body cannot have rotational inertia".into());
        }
        return Ok(());
    }
    let eig = m.symmetric_eigenvalues();
    let (a, b, c) = (eig[0], eig[1], eig[2]);
    let tol = 1e-9 * scale;
    if a < -tol || b < -tol || c < -tol {
        return Err(format!("inertia is not positive semi-definite (principal moments {a:.6e}, {b:.6e}, {c:.6e} kg·m²)"));
    }
    if a + b < c - tol || a + c < b - tol || b + c < a - tol {
        return Err(format!("principal moments {a:.6e}, {b:.6e}, {c:.6e} kg·m² break the triangle inequality"));
    }
    Ok(())
}
