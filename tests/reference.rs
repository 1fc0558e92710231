//! The engine against an established rigid-body library (Pinocchio 4.1.0): every file of
//! `tests/data/reference/`, every state, every quantity, joints matched by name, to 1e-9 relative.

mod common;

use common::{close, load_reference_urdf, reference_files};
use mintorque::dynamics::{aba::aba, crba::crba, kinematics, rnea::rnea, rnea_derivatives::rnea_derivatives, Data};
use mintorque::spatial::{Force, Vec3};
use mintorque::Model;
use serde_json::Value;

const TOL: f64 = 1e-9;

fn vec_of(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

fn vec3(v: &Value) -> Vec3 {
    let x = vec_of(v);
    Vec3::new(x[0], x[1], x[2])
}

struct Checker {
    file: String,
    worst: f64,
    failures: Vec<String>,
}

impl Checker {
    fn check(&mut self, what: &str, got: f64, want: f64) {
        let err = (got - want).abs() / want.abs().max(1.0);
        self.worst = self.worst.max(err);
        if !close(got, want, TOL) && self.failures.len() < 20 {
            self.failures.push(format!("{}: {what}: got {got:.15e}, want {want:.15e}", self.file));
        }
    }
}

/// Reference joint order → our dof index.
fn permutation(model: &Model, joints: &Value) -> Vec<usize> {
    joints
        .as_array()
        .unwrap()
        .iter()
        .map(|j| {
            let name = j["name"].as_str().unwrap();
            model.dof_index(name).unwrap_or_else(|| panic!("joint {name} missing from our model"))
        })
        .collect()
}

#[test]
fn dynamics_match_reference_data() {
    let mut summary = Vec::new();
    let mut all_failures = Vec::new();
    for path in reference_files() {
        let doc: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let urdf_path = path.parent().unwrap().join(doc["urdf"].as_str().unwrap());
        let model = load_reference_urdf(&urdf_path);
        let nv = model.nv();
        assert_eq!(nv, doc["nv"].as_u64().unwrap() as usize, "{}: DOF count", path.display());
        let perm = permutation(&model, &doc["joints"]);
        let gravity = vec3(&doc["gravity"]);
        let mut data = Data::new(&model);
        let mut c = Checker { file: path.file_name().unwrap().to_string_lossy().into(), worst: 0.0, failures: vec![] };
        c.check("total_mass", model.total_mass(), doc["total_mass"].as_f64().unwrap());
        c.check("root_link_mass", model.bodies[0].inertia.mass, doc["root_link_mass"].as_f64().unwrap());
        let ours = |x: &[f64]| {
            let mut out = vec![0.0; nv];
            for (r, &o) in perm.iter().enumerate() {
                out[o] = x[r];
            }
            out
        };
        let states = doc["states"].as_array().unwrap();
        assert!(!states.is_empty());
        for (s_idx, s) in states.iter().enumerate() {
            let (q, v, a) = (ours(&vec_of(&s["q"])), ours(&vec_of(&s["v"])), ours(&vec_of(&s["a"])));
            let tag = |what: &str| format!("state {s_idx} {what}");
            let vector = |c: &mut Checker, what: &str, got: &[f64], want: &Value| {
                for (r, w) in vec_of(want).iter().enumerate() {
                    c.check(&tag(&format!("{what}[{r}]")), got[perm[r]], *w);
                }
            };
            let matrix = |c: &mut Checker, what: &str, got: &nalgebra::DMatrix<f64>, want: &Value| {
                for (r, row) in want.as_array().unwrap().iter().enumerate() {
                    for (k, w) in vec_of(row).iter().enumerate() {
                        c.check(&tag(&format!("{what}[{r}][{k}]")), got[(perm[r], perm[k])], *w);
                    }
                }
            };
            // Inverse dynamics alone, and again with its derivatives (both must give the same τ).
            let tau = rnea(&model, &mut data, &q, &v, &a, &gravity, None).clone();
            vector(&mut c, "tau (rnea)", tau.as_slice(), &s["tau"]);
            rnea_derivatives(&model, &mut data, &q, &v, &a, &gravity, None);
            vector(&mut c, "tau (derivatives)", data.tau.as_slice(), &s["tau"]);
            matrix(&mut c, "dtau_dq", &data.dtau_dq, &s["dtau_dq"]);
            matrix(&mut c, "dtau_dv", &data.dtau_dv, &s["dtau_dv"]);
            matrix(&mut c, "M (derivatives)", &data.M, &s["M"]);
            let m = crba(&model, &mut data, &q).clone();
            matrix(&mut c, "M (crba)", &m, &s["M"]);
            let ddq = aba(&model, &mut data, &q, &v, &ours(&vec_of(&s["tau_rand"])), &gravity, None).clone();
            vector(&mut c, "ddq", ddq.as_slice(), &s["ddq"]);
            // Kinematics: link frames and joint frames.
            kinematics::placements(&model, &mut data, &q);
            for link in s["links"].as_array().unwrap() {
                let name = link["name"].as_str().unwrap();
                let f = model.frame_index(name).unwrap_or_else(|| panic!("frame {name} missing"));
                let x = kinematics::frame_placement(&model, &data, f);
                for (k, w) in vec_of(&link["rotation"]).iter().enumerate() {
                    c.check(&tag(&format!("link {name} R[{k}]")), x.rotation[(k / 3, k % 3)], *w);
                }
                for (k, w) in vec_of(&link["translation"]).iter().enumerate() {
                    c.check(&tag(&format!("link {name} p[{k}]")), x.translation[k], *w);
                }
            }
            for joint in s["joints_world"].as_array().unwrap() {
                let name = joint["name"].as_str().unwrap();
                let b = model.dof_index(name).unwrap() + 1;
                let x = data.oMi[b];
                for (k, w) in vec_of(&joint["rotation"]).iter().enumerate() {
                    c.check(&tag(&format!("joint {name} R[{k}]")), x.rotation[(k / 3, k % 3)], *w);
                }
                for (k, w) in vec_of(&joint["translation"]).iter().enumerate() {
                    c.check(&tag(&format!("joint {name} p[{k}]")), x.translation[k], *w);
                }
            }
            let com = kinematics::center_of_mass(&model, &data, false).unwrap();
            let com_all = kinematics::center_of_mass(&model, &data, true).unwrap();
            for k in 0..3 {
                c.check(&tag("com"), com[k], vec3(&s["com"])[k]);
                c.check(&tag("com_including_root"), com_all[k], vec3(&s["com_including_root"])[k]);
            }
            kinematics::velocities(&model, &mut data, &v);
            c.check(&tag("kinetic_energy"), kinematics::kinetic_energy(&model, &data), s["kinetic_energy"].as_f64().unwrap());
            // External force on one link, given in its joint's frame (moment about the joint origin).
            let fe = &s["fext"];
            let body = model.dof_index(fe["joint"].as_str().unwrap()).unwrap() + 1;
            let mut fext = vec![Force::ZERO; model.bodies.len()];
            fext[body] = Force::new(vec3(&fe["angular"]), vec3(&fe["linear"]));
            let tau_ext = rnea(&model, &mut data, &q, &v, &a, &gravity, Some(&fext)).clone();
            vector(&mut c, "fext tau", tau_ext.as_slice(), &fe["tau"]);
        }
        summary.push(format!("{}: {} states, worst relative error {:.2e}", c.file, states.len(), c.worst));
        all_failures.extend(c.failures);
    }
    println!("{}", summary.join("\n"));
    assert!(all_failures.is_empty(), "{} mismatches, first ones:\n{}", all_failures.len(), all_failures.join("\n"));
}
