//! Reports from a plan directory: ergonomics against analytic answers, every export format read back by
//! an independent parser (glTF by the `gltf` crate with validation, BVH by Python's `bvh` package, `.mot`
//! and CSV by hand), plots, and bad input. Records are synthetic (known motions on real models), so no
//! test needs a solve.

use mintorque::dynamics::{kinematics, Data};
use mintorque::model::human::{self, HumanParams, Structure};
use mintorque::model::{Body, Joint, JointKind, JointLimits, Model, Passive};
use mintorque::plan_dir::load as load_plan_dir;
use mintorque::report::ergonomics::{ergonomics, intervals_above, text_table};
use mintorque::report::export::{export, export_with, ChannelSet, Format, Options};
use mintorque::report::plots::{plot_svgs, plots};
use mintorque::report::record::{ContactRecord, PlanRecord, SampleRecord};
use mintorque::spatial::{axis_angle, Inertia, Mat3, Transform, Vec3};
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::PathBuf;
use std::process::Command;

// ---- Synthetic records ----

/// A record of `model` sampled at `times`, with `q(t)`, `q̇(t)`, `q̈(t)` and `τ(t)` given per joint.
fn record(model: &Model, times: &[f64], motion: impl Fn(usize, f64) -> [f64; 4]) -> PlanRecord {
    let nv = model.nv();
    let samples = times
        .iter()
        .map(|&t| {
            let v: Vec<[f64; 4]> = (0..nv).map(|i| motion(i, t)).collect();
            SampleRecord {
                t,
                q: v.iter().map(|x| x[0]).collect(),
                qd: v.iter().map(|x| x[1]).collect(),
                qdd: v.iter().map(|x| x[2]).collect(),
                tau: v.iter().map(|x| x[3]).collect(),
                contact_forces: vec![],
            }
        })
        .collect();
    PlanRecord {
        duration: times.last().copied().unwrap_or(0.0),
        gravity: [0.0, 0.0, -9.81],
        ..PlanRecord::of_samples(model, samples)
    }
}

fn grid(duration: f64, steps: usize) -> Vec<f64> {
    (0..=steps).map(|k| duration * k as f64 / steps as f64).collect()
}

/// Joint `i` swings as `aᵢ sin(ωt + φᵢ)` with different amplitudes and phases, large enough to pass a
/// half turn on some joints (so that unwrapped angles are tested).
fn swing(i: usize, t: f64) -> [f64; 4] {
    let (a, w, phase) = (0.4 + 0.35 * i as f64, 2.0 * PI, 0.3 * i as f64);
    let s = w * t + phase;
    [a * s.sin(), a * w * s.cos(), -a * w * w * s.sin(), 10.0 * (i as f64 + 1.0) * s.cos()]
}

/// One revolute about y with effort `effort`, hanging from a massless base.
fn one_joint(effort: f64) -> Model {
    let mut m = Model::new("one_joint", "base");
    let limits = JointLimits { effort, ..JointLimits::default() };
    m.add_body(
        Joint {
            name: "elbow".into(),
            kind: JointKind::Revolute,
            parent: 0,
            placement: Transform::IDENTITY,
            axis: Vec3::y(),
            limits,
            passive: Passive::default(),
            group: None,
        },
        Body {
            name: "forearm".into(),
            inertia: Inertia::new(1.0, Vec3::new(0.0, 0.0, -0.2), Mat3::identity() * 0.01),
            shapes: vec![],
        },
    );
    m
}

/// A revolute about a tilted axis (not a coordinate axis), then a prismatic joint sliding along x, then a
/// revolute about −x: Euler channels, position channels, sticks.
fn tilted_and_sliding() -> Model {
    let mut m = Model::new("tilted", "base");
    let body = |name: &str| Body {
        name: name.into(),
        inertia: Inertia::new(1.0, Vec3::new(0.0, 0.0, -0.3), Mat3::identity() * 0.02),
        shapes: vec![],
    };
    let joint = |name: &str, kind, parent, at: Vec3, axis: Vec3| Joint {
        name: name.into(),
        kind,
        parent,
        placement: Transform::from_translation(at),
        axis: axis.normalize(),
        limits: JointLimits::default(),
        passive: Passive::default(),
        group: None,
    };
    let a = m.add_body(joint("tilted", JointKind::Revolute, 0, Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 2.0, 2.0)), body("arm"));
    let b = m.add_body(joint("slide", JointKind::Prismatic, a, Vec3::new(0.0, 0.0, -0.6), Vec3::x()), body("carriage"));
    m.add_body(joint("twist", JointKind::Revolute, b, Vec3::new(0.1, 0.0, -0.2), -Vec3::x()), body("hand"));
    m
}

fn human_model(structure: Structure) -> Model {
    human::build(structure, HumanParams::default()).unwrap()
}

/// A scratch directory for this test process.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mintorque-report-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn assert_close(got: f64, want: f64, tol: f64, what: &str) {
    assert!((got - want).abs() <= tol, "{what}: got {got}, want {want} (tolerance {tol})");
}

// ---- Ergonomics ----

#[test]
fn time_above_the_limit_of_a_sine_torque_matches_the_analytic_crossings() {
    // τ = A sin(ωt) with A = 10 N·m, ω = 2π rad/s over one period; limit 6 N·m: |τ| > 6 on
    // (s, ½ − s) and (½ + s, 1 − s) with s = asin(0.6)/2π.
    let (amplitude, limit) = (10.0, 6.0);
    let model = one_joint(limit);
    let rec = record(&model, &grid(1.0, 1000), |_, t| [0.1 * t, 0.1, 0.0, amplitude * (2.0 * PI * t).sin()]);
    let e = ergonomics(&model, &rec, &BTreeMap::new()).unwrap();
    let j = &e.joints[0];
    let s = (limit / amplitude).asin() / (2.0 * PI);
    let want = [[s, 0.5 - s], [0.5 + s, 1.0 - s]];
    assert_eq!(j.intervals_above_limit.len(), 2, "{:?}", j.intervals_above_limit);
    for (got, want) in j.intervals_above_limit.iter().zip(want) {
        assert_close(got[0], want[0], 1e-5, "interval start");
        assert_close(got[1], want[1], 1e-5, "interval end");
    }
    assert_close(j.time_above_limit_s, 2.0 * (0.5 - 2.0 * s), 2e-5, "total time above");
    assert_eq!(j.strength_limit, Some(limit));
    assert_eq!(j.strength_source, Some("model effort limit"));
    assert_close(j.peak_abs_torque, amplitude, 1e-4, "peak");
    assert!(j.peak_time_s == 0.25 || j.peak_time_s == 0.75, "peak at {}", j.peak_time_s);
    assert_close(j.posture_at_peak["elbow"], (0.1 * j.peak_time_s).to_degrees(), 1e-9, "posture in degrees");
    assert_close(j.peak_fraction_of_limit.unwrap(), amplitude / limit, 1e-4, "fraction of limit");

    // An override takes the place of the model's limit.
    let overrides = BTreeMap::from([("elbow".to_string(), 8.0)]);
    let e = ergonomics(&model, &rec, &overrides).unwrap();
    let s = 0.8f64.asin() / (2.0 * PI);
    assert_eq!(e.joints[0].strength_source, Some("override"));
    assert_close(e.joints[0].time_above_limit_s, 2.0 * (0.5 - 2.0 * s), 2e-5, "time above the override");
    let table = text_table(&e);
    assert!(table.contains("elbow beyond its limit:"), "{table}");
}

#[test]
fn crossing_times_are_exact_for_piecewise_linear_torques() {
    // One segment that goes from above +1 to below −1: two pieces, in time order.
    assert_eq!(intervals_above(&[0.0, 1.0], &[2.0, -2.0], 1.0), vec![[0.0, 0.25], [0.75, 1.0]]);
    // Pieces that touch across samples are merged.
    assert_eq!(intervals_above(&[0.0, 1.0, 2.0, 3.0], &[0.0, 2.0, 2.0, 0.0], 1.0), vec![[0.5, 2.5]]);
    assert!(intervals_above(&[0.0, 1.0], &[1.0, 1.0], 1.0).is_empty(), "at the limit is not above it");
}

#[test]
fn work_of_a_constant_torque_at_constant_speed_is_torque_times_speed_times_time() {
    // τ = k = 3 N·m, q̇ = c = 2 rad/s for T = 2 s: W = kcT = 12 J, power 6 W throughout.
    let model = one_joint(f64::INFINITY);
    let rec = record(&model, &grid(2.0, 50), |_, t| [2.0 * t, 2.0, 0.0, 3.0]);
    let e = ergonomics(&model, &rec, &BTreeMap::new()).unwrap();
    assert_close(e.joints[0].absolute_work_j, 12.0, 1e-12, "absolute work");
    assert_close(e.total_positive_work_j, 12.0, 1e-12, "positive work");
    assert_close(e.joints[0].peak_power_w, 6.0, 1e-12, "peak power");
    assert_eq!(e.joints[0].strength_limit, None);
    assert_eq!(e.joints[0].time_above_limit_s.to_bits(), 0.0f64.to_bits(), "no limit, no time above it (and not −0)");
    assert_eq!(e.peak_power.as_ref().map(|p| p.joint.as_str()), Some("elbow"));

    // Braking (τ against q̇) does negative work: none of it is positive.
    let braking = record(&model, &grid(2.0, 50), |_, t| [2.0 * t, 2.0, 0.0, -3.0]);
    let e = ergonomics(&model, &braking, &BTreeMap::new()).unwrap();
    assert_close(e.joints[0].absolute_work_j, 12.0, 1e-12, "absolute work when braking");
    assert_close(e.total_positive_work_j, 0.0, 1e-12, "positive work when braking");

    // Power changing sign between two samples: −½ → ½ W over 1 s gives ¼ J absolute, ⅛ J positive.
    let crossing = record(&model, &[0.0, 1.0], |_, t| [0.0, t - 0.5, 0.0, 1.0]);
    let e = ergonomics(&model, &crossing, &BTreeMap::new()).unwrap();
    assert_close(e.joints[0].absolute_work_j, 0.25, 1e-15, "absolute work across a sign change");
    assert_close(e.joints[0].positive_work_j, 0.125, 1e-15, "positive work across a sign change");
}

#[test]
fn ergonomics_of_the_human_uses_its_documented_strengths_and_serialises() {
    let model = human_model(Structure::Sagittal);
    let rec = record(&model, &grid(1.0, 100), swing);
    let e = ergonomics(&model, &rec, &BTreeMap::new()).unwrap();
    for (j, joint) in e.joints.iter().zip(&model.joints[1..]) {
        assert_eq!(j.strength_limit, Some(joint.limits.effort), "{}", j.name);
        assert_eq!(j.posture_at_peak.len(), model.nv());
    }
    let json = serde_json::to_value(&e).unwrap();
    assert!(json["joints"][0]["intervals_above_limit"].is_array());
    assert!(json["total_positive_work_j"].is_number());
}

#[test]
fn ergonomics_refuses_overrides_for_unknown_joints_and_bad_values() {
    let model = one_joint(10.0);
    let rec = record(&model, &grid(1.0, 10), |_, _| [0.0; 4]);
    let unknown = ergonomics(&model, &rec, &BTreeMap::from([("knee".to_string(), 5.0)])).unwrap_err().to_string();
    assert!(unknown.contains("no joint called \"knee\"") && unknown.contains("elbow"), "{unknown}");
    let negative = ergonomics(&model, &rec, &BTreeMap::from([("elbow".to_string(), -5.0)])).unwrap_err().to_string();
    assert!(negative.contains("positive"), "{negative}");
}

// ---- Export: .mot and CSV ----

#[test]
fn mot_has_the_opensim_header_and_angles_in_degrees() {
    let model = human_model(Structure::Sagittal);
    let rec = record(&model, &grid(1.0, 40), swing);
    let (name, bytes) = export(&model, &rec, Format::Mot).unwrap();
    assert_eq!(name, "human_sagittal.mot");
    let text = String::from_utf8(bytes).unwrap();
    let (header, table) = text.split_once("endheader\n").expect("an endheader line");
    let keys: BTreeMap<&str, &str> = header.lines().filter_map(|l| l.split_once('=')).collect();
    assert!(!header.lines().next().unwrap().contains('='), "the first line names the motion");
    assert_eq!(keys["version"], "1");
    assert_eq!(keys["nRows"], "41");
    assert_eq!(keys["nColumns"], (model.nv() + 1).to_string());
    assert_eq!(keys["inDegrees"], "yes");
    let mut lines = table.lines();
    let columns: Vec<&str> = lines.next().unwrap().split('\t').collect();
    assert_eq!(columns[0], "time");
    assert_eq!(columns[1..], model.joint_names()[..]);
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split('\t').map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 41);
    for k in [0, 13, 40] {
        assert_close(rows[k][0], rec.samples[k].t, 1e-6, "time");
        for i in 0..model.nv() {
            assert_close(rows[k][i + 1], rec.samples[k].q[i].to_degrees(), 1e-8, "angle");
        }
    }
}

#[test]
fn csv_has_every_joints_columns_with_units() {
    let model = tilted_and_sliding();
    let mut rec = record(&model, &grid(1.0, 20), swing);
    rec.contacts = vec![ContactRecord { name: "grip".into(), frame: "hand".into(), target: [0.0; 3], normal: None }];
    for s in &mut rec.samples {
        s.contact_forces = vec![[1.0, 2.0, s.t]];
    }
    let (name, bytes) = export(&model, &rec, Format::from_name("CSV").unwrap()).unwrap();
    assert_eq!(name, "tilted.csv");
    let text = String::from_utf8(bytes).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[..5], ["time_s", "tilted.q_deg", "tilted.qd_deg_s", "tilted.qdd_deg_s2", "tilted.tau_Nm"]);
    assert_eq!(header[5..9], ["slide.q_m", "slide.qd_m_s", "slide.qdd_m_s2", "slide.tau_N"]);
    assert_eq!(header[header.len() - 3..], ["grip.fx_N", "grip.fy_N", "grip.fz_N"]);
    let row: Vec<f64> = lines.nth(7).unwrap().split(',').map(|v| v.parse().unwrap()).collect();
    let s = &rec.samples[7];
    assert_close(row[1], s.q[0].to_degrees(), 1e-8, "tilted.q_deg");
    assert_close(row[3], s.qdd[0].to_degrees(), 1e-6, "tilted.qdd_deg_s2");
    assert_close(row[5], s.q[1], 1e-9, "slide.q_m");
    assert_close(row[8], s.tau[1], 1e-9, "slide.tau_N");
    assert_close(row[row.len() - 1], s.t, 1e-9, "grip.fz_N");
}

// ---- Export: glTF ----

/// One node's keyframes: rotations (x, y, z, w) and translations.
#[derive(Default)]
struct NodeKeys {
    rotations: Vec<[f32; 4]>,
    translations: Vec<[f32; 3]>,
}

/// The animated rotations and translations of a `.glb`, read by the `gltf` crate (which validates it).
struct GltfMotion {
    times: Vec<f32>,
    /// Node name → its keyframes.
    channels: BTreeMap<String, NodeKeys>,
    meshes_on: Vec<String>,
}

fn read_glb(bytes: &[u8]) -> GltfMotion {
    let doc = gltf::Gltf::from_slice(bytes).expect("a valid glTF 2.0 binary");
    let blob = doc.blob.clone().expect("a BIN chunk");
    let animation = doc.animations().next().expect("an animation");
    let mut motion = GltfMotion { times: vec![], channels: BTreeMap::new(), meshes_on: vec![] };
    for channel in animation.channels() {
        let reader = channel.reader(|_| Some(&blob));
        motion.times = reader.read_inputs().expect("keyframe times").collect();
        let node = channel.target().node().name().unwrap_or_default().to_string();
        let entry = motion.channels.entry(node).or_default();
        match reader.read_outputs().expect("keyframe values") {
            gltf::animation::util::ReadOutputs::Rotations(r) => entry.rotations = r.into_f32().collect(),
            gltf::animation::util::ReadOutputs::Translations(t) => entry.translations = t.collect(),
            _ => panic!("only rotations and translations are animated"),
        }
    }
    motion.meshes_on = doc.nodes().filter(|n| n.mesh().is_some()).filter_map(|n| n.name().map(String::from)).collect();
    motion
}

/// The joint angle about `axis` of the rotation `placementᵀ·R(quaternion)`, within (−π, π].
fn angle_about(quaternion: [f32; 4], placement: &Mat3, axis: &Vec3) -> f64 {
    let [x, y, z, w] = quaternion.map(f64::from);
    let r = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)).to_rotation_matrix().into_inner();
    let relative = placement.transpose() * r;
    let (s, c) = ((relative - relative.transpose()) * 0.5, (relative.trace() - 1.0) / 2.0);
    let sin_about = Vec3::new(s[(2, 1)], s[(0, 2)], s[(1, 0)]).dot(axis);
    sin_about.atan2(c)
}

fn wrapped(a: f64) -> f64 {
    let w = a.rem_euclid(2.0 * PI);
    if w > PI {
        w - 2.0 * PI
    } else {
        w
    }
}

#[test]
fn gltf_reads_back_valid_with_the_joint_angles_of_the_plan() {
    for model in [human_model(Structure::FreeArms), tilted_and_sliding()] {
        let rec = record(&model, &grid(1.0, 60), swing);
        let (name, bytes) = export(&model, &rec, Format::from_name("glb").unwrap()).unwrap();
        assert!(name.ends_with(".glb"));
        let motion = read_glb(&bytes);
        assert_eq!(motion.times.len(), rec.samples.len());
        for (i, joint) in model.joints.iter().enumerate().skip(1) {
            let body = &model.bodies[i].name;
            let NodeKeys { rotations, translations } = &motion.channels[body];
            for k in [0, 17, 45, 60] {
                let q = rec.samples[k].q[i - 1];
                match joint.kind {
                    JointKind::Prismatic => {
                        let want = joint.placement.translation + joint.axis * q;
                        let got = Vec3::new(translations[k][0].into(), translations[k][1].into(), translations[k][2].into());
                        assert!((got - want).norm() < 1e-6, "{} at frame {k}: {got} vs {want}", joint.name);
                    }
                    _ => {
                        let got = angle_about(rotations[k], &joint.placement.rotation, &joint.axis);
                        assert_close(wrapped(got - q), 0.0, 1e-6, &format!("{} at frame {k}", joint.name));
                    }
                }
            }
        }
        // Every body with shapes, and every body without but with a segment to draw, has a mesh.
        for body in &model.bodies {
            if !body.shapes.is_empty() || body.inertia.mass > 0.0 {
                assert!(motion.meshes_on.contains(&body.name), "{} has no mesh", body.name);
            }
        }
    }
}

/// A node's local matrix at keyframe `k`: its animated rotation/translation there, else its own TRS.
fn node_local(node: &gltf::Node, motion: &GltfMotion, k: usize) -> nalgebra::Matrix4<f64> {
    let (t, r, _) = node.transform().decomposed();
    let keys = node.name().and_then(|n| motion.channels.get(n));
    let r = keys.and_then(|c| c.rotations.get(k)).copied().unwrap_or(r);
    let t = keys.and_then(|c| c.translations.get(k)).copied().unwrap_or(t);
    let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(r[3], r[0], r[1], r[2]).cast::<f64>());
    nalgebra::Isometry3::from_parts(nalgebra::Translation3::new(t[0].into(), t[1].into(), t[2].into()), q).to_homogeneous()
}

/// Every node's scene matrix at keyframe `k` (`None` for a node outside the scene's tree).
fn node_worlds(doc: &gltf::Document, motion: &GltfMotion, k: usize) -> Vec<nalgebra::Matrix4<f64>> {
    let mut world = vec![nalgebra::Matrix4::identity(); doc.nodes().len()];
    let mut stack: Vec<(gltf::Node, nalgebra::Matrix4<f64>)> =
        doc.default_scene().unwrap().nodes().map(|n| (n, nalgebra::Matrix4::identity())).collect();
    while let Some((node, parent)) = stack.pop() {
        world[node.index()] = parent * node_local(&node, motion, k);
        stack.extend(node.children().map(|c| (c, world[node.index()])));
    }
    world
}

fn point(m: &nalgebra::Matrix4<f64>, p: [f32; 3]) -> Vec3 {
    let h = m * nalgebra::Vector4::new(p[0].into(), p[1].into(), p[2].into(), 1.0);
    Vec3::new(h.x, h.y, h.z)
}

#[test]
fn gltf_skinned_mesh_is_bound_rigidly_and_moves_onto_the_rigid_parts() {
    let model = human_model(Structure::WholeBody);
    let rec = record(&model, &grid(1.0, 60), swing);
    let (_, bytes) = export(&model, &rec, Format::Gltf).unwrap();
    let motion = read_glb(&bytes);
    let doc = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = doc.blob.clone().unwrap();
    let skin = doc.skins().next().expect("a skin");
    let joints: Vec<usize> = skin.joints().map(|j| j.index()).collect();
    let names: Vec<&str> = skin.joints().map(|j| j.name().unwrap()).collect();
    assert_eq!(names, model.bodies.iter().map(|b| b.name.as_str()).collect::<Vec<_>>(), "one joint per body, in order");
    let reader = skin.reader(|_| Some(&blob));
    let inverse_bind: Vec<nalgebra::Matrix4<f64>> =
        reader.read_inverse_bind_matrices().unwrap().map(|m| nalgebra::Matrix4::from(m).cast::<f64>()).collect();
    // The inverse bind matrices are the inverses of the joints' scene matrices at rest (q = 0: the nodes'
    // own TRS, without the animation).
    let rest = node_worlds(&doc, &GltfMotion { times: vec![], channels: BTreeMap::new(), meshes_on: vec![] }, 0);
    for (j, ibm) in joints.iter().zip(&inverse_bind) {
        assert!((ibm * rest[*j] - nalgebra::Matrix4::identity()).norm() < 1e-5, "joint {j}");
    }
    let skinned_node = doc.nodes().find(|n| n.skin().is_some()).expect("a skinned node");
    let primitive = skinned_node.mesh().unwrap().primitives().next().unwrap();
    let r = primitive.reader(|_| Some(&blob));
    let positions: Vec<[f32; 3]> = r.read_positions().unwrap().collect();
    let vertex_joints: Vec<[u16; 4]> = r.read_joints(0).unwrap().into_u16().collect();
    let weights: Vec<[f32; 4]> = r.read_weights(0).unwrap().into_f32().collect();
    assert!(weights.iter().all(|w| *w == [1.0, 0.0, 0.0, 0.0]), "each vertex bound to one joint, rigidly");
    for k in [0, 23, 47] {
        let world = node_worlds(&doc, &motion, k);
        // The rigid parts' vertices at keyframe k, body by body in node order: where the skin must put them.
        let mut rigid = Vec::new();
        for (b, &node) in joints.iter().enumerate() {
            let Some(mesh) = doc.nodes().nth(node).unwrap().mesh() else { continue };
            let p = mesh.primitives().next().unwrap();
            let local: Vec<[f32; 3]> = p.reader(|_| Some(&blob)).read_positions().unwrap().collect();
            rigid.extend(local.iter().map(|v| (b, point(&world[node], *v))));
        }
        assert_eq!(rigid.len(), positions.len());
        let mut moved = 0.0f64;
        for (v, (&(b, want), bound)) in rigid.iter().zip(&vertex_joints).enumerate() {
            let j = bound[0] as usize;
            assert_eq!(j, b, "vertex {v} bound to the joint of its body");
            let got = point(&(world[joints[j]] * inverse_bind[j]), positions[v]);
            assert!((got - want).norm() < 2e-5, "vertex {v} at keyframe {k}: skinned {got} vs rigid {want}");
            moved = moved.max((got - point(&nalgebra::Matrix4::identity(), positions[v])).norm());
        }
        // The opposite: the motion does move the skinned vertices away from the bind pose.
        assert!(moved > 0.1, "keyframe {k}: the skin stays at its bind pose ({moved} m)");
    }
}

// ---- Export: BVH, read back by Python's `bvh` package ----

const BVH_READER: &str = r#"
import json, sys
from bvh import Bvh
with open(sys.argv[1]) as f:
    mocap = Bvh(f.read())
frames = [int(k) for k in sys.argv[2].split(',')]
joints = []
for name in mocap.get_joints_names():
    channels = mocap.joint_channels(name)
    parent = mocap.joint_parent(name)
    joints.append({
        'name': name,
        'parent': parent.name if parent is not None else None,
        'offset': list(mocap.joint_offset(name)),
        'channels': channels,
        'values': [mocap.frame_joint_channels(k, name, channels) for k in frames],
    })
print(json.dumps({'frames': mocap.nframes, 'frame_time': mocap.frame_time, 'joints': joints}))
"#;

/// Python's `bvh` package's reading of `path` at `frames`. Fails (never skips) without python3 or the
/// package: `scripts/test-deps.sh` installs it, and CI runs that script first.
fn read_bvh_with_python(path: &std::path::Path, frames: &[usize]) -> serde_json::Value {
    let frames: Vec<String> = frames.iter().map(|k| k.to_string()).collect();
    let output = Command::new("python3")
        .arg("-c")
        .arg(BVH_READER)
        .arg(path)
        .arg(frames.join(","))
        .output()
        .expect("python3 is needed to read BVH files back (see scripts/test-deps.sh)");
    assert!(
        output.status.success(),
        "Python's bvh package could not read the file (install it with `bash scripts/test-deps.sh`):\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).unwrap()
}

/// Model (Z up) to BVH (Y up).
fn y_up() -> Mat3 {
    Mat3::new(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0)
}

/// `R = R_c1(v1)·R_c2(v2)·R_c3(v3)` for rotation channels named like "Zrotation" (degrees).
fn rotation_from_channels(channels: &[String], values: &[f64]) -> Mat3 {
    channels.iter().zip(values).filter(|(c, _)| c.ends_with("rotation")).fold(Mat3::identity(), |r, (c, v)| {
        let axis = match &c[..1] {
            "X" => Vec3::x(),
            "Y" => Vec3::y(),
            _ => Vec3::z(),
        };
        r * axis_angle(&axis, v.to_radians())
    })
}

fn strings(v: &serde_json::Value) -> Vec<String> {
    v.as_array().unwrap().iter().map(|s| s.as_str().unwrap().to_string()).collect()
}

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|s| s.as_f64().unwrap()).collect()
}

/// The model joints a BVH joint stands for: the joint of that name, or the revolutes of that group.
fn joints_named(model: &Model, name: &str) -> Vec<usize> {
    match model.dof_index(name) {
        Some(i) => vec![i + 1],
        None => (1..model.joints.len()).filter(|&i| model.joints[i].group.as_deref() == Some(name)).collect(),
    }
}

/// The BVH joint `name` as model joints: the root's chain (from body 0 down to the body it is named after,
/// when the root is merged), or the joint of that name, or the revolutes of that group.
fn bvh_chain(model: &Model, name: &str, is_root: bool) -> Vec<usize> {
    if is_root {
        let mut chain = Vec::new();
        let mut b = model.body_index(name).unwrap_or_else(|| panic!("BVH root {name} is no body"));
        while b != 0 {
            chain.insert(0, b);
            b = model.joints[b].parent;
        }
        return chain;
    }
    joints_named(model, name)
}

/// The model frame a BVH joint stands for when it is a welded part (no joint or group of its name).
fn welded_part(model: &Model, name: &str, is_root: bool) -> Option<usize> {
    if is_root || !joints_named(model, name).is_empty() {
        return None;
    }
    model.frames.iter().position(|f| f.name == name && f.welded_to.is_some())
}

/// World placements of the BVH joints at frame `f` (the parsed file's `values[f]`) by BVH's own forward
/// kinematics: `W = W_parent · Trans(position channels, else OFFSET) · Π Rot(rotation channels)`, in the
/// file's axes and unit. A position channel holds that coordinate in full; missing axes keep the OFFSET's.
fn bvh_forward_kinematics(parsed: &serde_json::Value, f: usize) -> BTreeMap<String, Transform> {
    let mut world: BTreeMap<String, Transform> = BTreeMap::new();
    for joint in parsed["joints"].as_array().unwrap() {
        let channels = strings(&joint["channels"]);
        let values = floats(&joint["values"][f]);
        let mut position = Vec3::from_vec(floats(&joint["offset"]));
        for (c, v) in channels.iter().zip(&values).filter(|(c, _)| c.ends_with("position")) {
            position["XYZ".find(&c[..1]).unwrap()] = *v;
        }
        let local = Transform::new(rotation_from_channels(&channels, &values), position);
        let parent = joint["parent"].as_str().map_or(Transform::IDENTITY, |p| world[p]);
        world.insert(joint["name"].as_str().unwrap().to_string(), parent.compose(&local));
    }
    world
}

/// Writes the BVH of `model` under `motion` with `options`, reads it back with Python at `frames`.
fn bvh_read_back(model: &Model, rec: &PlanRecord, options: &Options, tag: &str, frames: &[usize]) -> (serde_json::Value, String) {
    let (name, bytes) = export_with(model, rec, Format::Bvh, options).unwrap();
    assert!(name.ends_with(".bvh"));
    let path = scratch(tag).join(name);
    std::fs::write(&path, &bytes).unwrap();
    (read_bvh_with_python(&path, frames), String::from_utf8(bytes).unwrap())
}

/// Every body's world placement at `q`, by the dynamics engine's forward kinematics (`data.oMi`).
fn body_placements(model: &Model, q: &[f64]) -> Vec<Transform> {
    let mut data = Data::new(model);
    kinematics::placements(model, &mut data, q);
    data.oMi.clone()
}

/// Checks, at `frames` (times `times[k]`), that every BVH joint's world position is the model's joint
/// position `C·Wᵢ(q).t` (× `scale`, i the chain's last body) and its world rotation the chain body's turn from rest `C·G·Cᵀ` with
/// `G = W(q)·W(0)ᵀ`, with q the plan's `q_at(t)`.
fn assert_bvh_matches_the_model(
    model: &Model,
    parsed: &serde_json::Value,
    frames: &[usize],
    q_at: impl Fn(usize) -> Vec<f64>,
    scale: f64,
    tag: &str,
) {
    let c = y_up();
    let rest = body_placements(model, &vec![0.0; model.nv()]);
    for (f, &k) in frames.iter().enumerate() {
        let bvh_world = bvh_forward_kinematics(parsed, f);
        let world = body_placements(model, &q_at(k));
        for (n, joint) in parsed["joints"].as_array().unwrap().iter().enumerate() {
            let name = joint["name"].as_str().unwrap();
            let got = &bvh_world[name];
            // A welded part sits at its frame and turns with its body.
            let part = welded_part(model, name, n == 0);
            let chain = if part.is_some() { vec![] } else { bvh_chain(model, name, n == 0) };
            // The joints of a chain share one origin but for its slides: the head is its last body's origin.
            let last = part.map_or(chain.last().copied().unwrap_or(0), |f| model.frames[f].body);
            let at = part.map_or(world[last], |f| world[last].compose(&model.frames[f].placement));
            let want = c * at.translation * scale;
            assert!((got.translation - want).norm() < 1e-4 * scale, "{tag}: {name} at frame {k}: {} vs {want}", got.translation);
            let turn = c * world[last].rotation * rest[last].rotation.transpose() * c.transpose();
            assert!((got.rotation - turn).norm() < 1e-5, "{tag}: {name}'s rotation at frame {k}");
        }
    }
}

/// Writes the BVH of `model` swinging (default options: centimetres, the plan's 50 Hz), reads it back with
/// Python and checks the frame count and time and, by forward kinematics, every joint's world pose.
fn check_bvh_round_trip(model: &Model, tag: &str) -> serde_json::Value {
    let rec = record(model, &grid(1.0, 50), swing);
    let frames = [0, 9, 26, 50];
    let (parsed, _) = bvh_read_back(model, &rec, &Options::default(), tag, &frames);
    assert_eq!(parsed["frames"], 51);
    assert_close(parsed["frame_time"].as_f64().unwrap(), 0.02, 1e-9, "frame time");
    assert_bvh_matches_the_model(model, &parsed, &frames, |k| rec.samples[k].q.clone(), 100.0, tag);
    parsed
}

#[test]
fn bvh_of_the_sagittal_human_holds_the_joint_angles_themselves() {
    let model = human_model(Structure::Sagittal);
    let parsed = check_bvh_round_trip(&model, "bvh-sagittal");
    let joints = parsed["joints"].as_array().unwrap();
    assert_eq!(joints[0]["name"], model.bodies[0].name.as_str());
    // The feet stay on the ground: a root that never moves has no channels.
    assert!(strings(&joints[0]["channels"]).is_empty());
    // Every joint turns about the model's ±y, which is BVH's ∓z: the Zrotation channel is ∓q in degrees.
    let rec = record(&model, &grid(1.0, 50), swing);
    for joint in joints[1..].iter().filter(|j| !strings(&j["channels"]).is_empty()) {
        let i = model.dof_index(joint["name"].as_str().unwrap()).unwrap();
        let sign = -model.joints[i + 1].axis.y;
        assert_eq!(strings(&joint["channels"])[0], "Zrotation");
        for (k, values) in [0, 9, 26, 50].iter().zip(joint["values"].as_array().unwrap()) {
            assert_close(floats(values)[0], sign * rec.samples[*k].q[i].to_degrees(), 1e-5, "joint angle");
        }
    }
}

/// The BVH joint `name`'s height above the floor at rest (cm): the sum of its and its ancestors' OFFSETs' y.
fn rest_height(parsed: &serde_json::Value, name: &str) -> f64 {
    let joints = parsed["joints"].as_array().unwrap();
    let joint = joints.iter().find(|j| j["name"] == name).unwrap_or_else(|| panic!("no BVH joint {name}"));
    let up = joint["parent"].as_str().map_or(0.0, |p| rest_height(parsed, p));
    up + floats(&joint["offset"])[1]
}

#[test]
fn bvh_of_the_sagittal_human_carries_its_spine_neck_and_head() {
    let params = HumanParams { stature_m: 1.70, ..HumanParams::default() };
    let model = human::build(Structure::Sagittal, params).unwrap();
    let parsed = check_bvh_round_trip(&model, "bvh-head");
    // Upper torso, neck and head hang from the lumbar joint in a chain, still (no channels).
    for (name, parent) in [("upper_torso", "lumbar"), ("neck", "upper_torso"), ("head", "neck")] {
        let joint = parsed["joints"].as_array().unwrap().iter().find(|j| j["name"] == name);
        let joint = joint.unwrap_or_else(|| panic!("no BVH joint {name}"));
        assert_eq!(joint["parent"], parent);
        assert!(strings(&joint["channels"]).is_empty(), "{name} has channels");
    }
    // Table I scaled to 1.70 m: lower, middle and upper torso and the neck, 12.16 + 15.13 + 27.12 + 9 cm
    // at 1.83 m, from the hip joint to the base of the skull.
    let above_hips = rest_height(&parsed, "head") - rest_height(&parsed, "hip");
    assert_close(above_hips, 63.41 * 1.70 / 1.83, 1e-3, "head joint above the hips (cm)");
    // The head's End Site is the vertex: the skeleton is as tall as the figure.
    let (_, text) = bvh_read_back(&model, &record(&model, &grid(1.0, 50), swing), &Options::default(), "bvh-head", &[0]);
    let end_site = &text[text.find("JOINT head").unwrap()..];
    let end_site = &end_site[end_site.find("End Site").unwrap()..];
    let offset = end_site.lines().find_map(|l| l.trim().strip_prefix("OFFSET")).unwrap();
    let end: Vec<f64> = offset.split_whitespace().map(|v| v.parse().unwrap()).collect();
    assert_close(rest_height(&parsed, "head") + end[1], 170.0, 1e-3, "top of the head (cm)");
}

#[test]
fn bvh_collapses_an_anatomical_joint_into_one_bvh_joint() {
    let model = human_model(Structure::FreeArms);
    let parsed = check_bvh_round_trip(&model, "bvh-free-arms");
    let names: Vec<String> =
        parsed["joints"].as_array().unwrap().iter().map(|j| j["name"].as_str().unwrap().to_string()).collect();
    let groups: Vec<&str> = model.joints.iter().filter_map(|j| j.group.as_deref()).collect();
    assert!(!groups.is_empty());
    for g in groups {
        assert!(names.iter().any(|n| n == g), "{g} missing from {names:?}");
    }
    assert!(names.iter().all(|n| model.dof_index(n).is_none_or(|i| model.joints[i + 1].group.is_none())), "{names:?}");
}

#[test]
fn bvh_writes_euler_angles_for_a_tilted_axis_and_positions_for_a_prismatic_joint() {
    let parsed = check_bvh_round_trip(&tilted_and_sliding(), "bvh-tilted");
    let slide = parsed["joints"].as_array().unwrap().iter().find(|j| j["name"] == "slide").unwrap();
    assert_eq!(strings(&slide["channels"])[..3], ["Xposition", "Yposition", "Zposition"]);
}

/// Swing only the degrees of freedom named in `moving`; every other stays at 0.
fn swing_only(model: &Model, moving: &[&str]) -> PlanRecord {
    let idx: Vec<usize> = moving.iter().map(|n| model.dof_index(n).unwrap_or_else(|| panic!("no joint {n}"))).collect();
    record(model, &grid(1.0, 50), |i, t| if idx.contains(&i) { swing(i, t) } else { [0.0; 4] })
}

fn channels_of(parsed: &serde_json::Value, name: &str) -> Vec<String> {
    let joint = parsed["joints"].as_array().unwrap().iter().find(|j| j["name"] == name);
    strings(&joint.unwrap_or_else(|| panic!("no BVH joint {name}"))["channels"])
}

#[test]
fn bvh_of_the_whole_body_has_every_body_to_the_head_and_hands_and_its_forward_kinematics() {
    let params = HumanParams::default();
    for (model, tag) in [
        (human_model(Structure::WholeBody), "bvh-whole"),
        (human::build_free(Structure::WholeBody, params).unwrap(), "bvh-free"),
        (human_model(Structure::Hanging), "bvh-hanging"),
    ] {
        let parsed = check_bvh_round_trip(&model, tag);
        let names: Vec<&str> = parsed["joints"].as_array().unwrap().iter().map(|j| j["name"].as_str().unwrap()).collect();
        let drawn = model.bodies.iter().filter(|b| b.inertia.mass > 0.0 || !b.shapes.is_empty()).count();
        let parts = names.iter().enumerate().filter(|&(n, name)| welded_part(&model, name, n == 0).is_some()).count();
        assert_eq!(names.len() - parts, drawn, "{tag}: one BVH joint per body with mass or a drawing: {names:?}");
        if tag != "bvh-hanging" {
            for part in ["lumbar", "thoracic", "neck", "l_wrist", "r_wrist", "l_shoulder"] {
                assert!(names.contains(&part), "{tag}: {part} missing from {names:?}");
            }
        }
    }
}

#[test]
fn bvh_gives_channels_only_to_the_joints_that_move() {
    let model = human::build_free(Structure::WholeBody, HumanParams::default()).unwrap();
    let rec = swing_only(&model, &["root_yaw", "l_knee", "r_shoulder_y"]);
    let (parsed, _) = bvh_read_back(&model, &rec, &Options::default(), "bvh-still", &[0, 26, 50]);
    assert_bvh_matches_the_model(&model, &parsed, &[0, 26, 50], |k| rec.samples[k].q.clone(), 100.0, "still joints");
    let root = parsed["joints"][0]["name"].as_str().unwrap().to_string();
    // The root turns but does not slide: three rotation channels, no positions.
    assert_eq!(channels_of(&parsed, &root), ["Yrotation", "Xrotation", "Zrotation"]);
    assert_eq!(channels_of(&parsed, "l_knee").len(), 3);
    assert_eq!(channels_of(&parsed, "r_shoulder").len(), 3);
    for joint in parsed["joints"].as_array().unwrap() {
        let name = joint["name"].as_str().unwrap();
        if ![root.as_str(), "l_knee", "r_shoulder"].contains(&name) {
            assert!(strings(&joint["channels"]).is_empty(), "{name} never moves but has channels");
        }
    }
    // One channel per moving DOF on request: the knee (about the model's y, BVH's −z) gets Zrotation only.
    let per_dof = Options { channels: ChannelSet::PerDof, ..Options::default() };
    let (parsed, _) = bvh_read_back(&model, &rec, &per_dof, "bvh-per-dof", &[0, 26, 50]);
    assert_bvh_matches_the_model(&model, &parsed, &[0, 26, 50], |k| rec.samples[k].q.clone(), 100.0, "per dof");
    assert_eq!(channels_of(&parsed, "l_knee"), ["Zrotation"]);
    assert_eq!(channels_of(&parsed, &root), ["Yrotation"]);
    // A root that slides gets its position channels first.
    let rec = swing_only(&model, &["root_z", "l_knee"]);
    let (parsed, _) = bvh_read_back(&model, &rec, &Options::default(), "bvh-slide", &[0, 26, 50]);
    assert_bvh_matches_the_model(&model, &parsed, &[0, 26, 50], |k| rec.samples[k].q.clone(), 100.0, "sliding root");
    assert_eq!(channels_of(&parsed, &root), ["Xposition", "Yposition", "Zposition"]);
}

#[test]
fn bvh_frame_rate_and_length_unit_are_the_ones_asked_for() {
    let model = human_model(Structure::Sagittal);
    let rec = record(&model, &grid(1.0, 50), swing);
    let options = Options { fps: Some(30.0), length: mintorque::report::export::LengthUnit::Metre, ..Options::default() };
    let frames = [0, 7, 19, 30];
    let (parsed, text) = bvh_read_back(&model, &rec, &options, "bvh-fps", &frames);
    assert_eq!(parsed["frames"], 31);
    assert_close(parsed["frame_time"].as_f64().unwrap(), 1.0 / 30.0, 1e-9, "frame time");
    assert!(text.contains("Frame Time: 0.033333333"));
    // Frame k is the motion at k/30 s, between the 50 Hz samples: resampled by the samples' q and q̇
    // (a linear blend, off by up to ~5e-3 rad per joint here, would miss the 0.1 mm check by millimetres).
    let exact = |k: usize| (0..model.nv()).map(|i| swing(i, k as f64 / 30.0)[0]).collect::<Vec<f64>>();
    assert_bvh_matches_the_model(&model, &parsed, &frames, exact, 1.0, "30 fps, metres");
    let (in_cm, _) = bvh_read_back(&model, &rec, &Options::default(), "bvh-cm", &[0]);
    let metres = floats(&parsed["joints"][2]["offset"]);
    let centimetres = floats(&in_cm["joints"][2]["offset"]);
    assert!(metres[1] > 0.3 && (centimetres[1] - 100.0 * metres[1]).abs() < 1e-4, "{metres:?} vs {centimetres:?}");
    for bad in [0.0, -30.0, f64::NAN] {
        let err = export_with(&model, &rec, Format::Bvh, &Options { fps: Some(bad), ..Options::default() }).unwrap_err();
        assert!(err.to_string().contains("frames per second"), "{err}");
    }
    let err = export_with(&model, &rec, Format::Csv, &Options { fps: Some(30.0), ..Options::default() }).unwrap_err();
    assert!(err.to_string().contains("--fps") && err.to_string().contains("bvh only"), "{err}");
}

// ---- Export: CSV options ----

fn csv_rows(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    (header, lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect())
}

#[test]
fn csv_options_choose_the_angle_unit_columns_joints_and_rate() {
    use mintorque::report::export::{AngleUnit, Column, CsvOptions};
    let model = human_model(Structure::Sagittal);
    let rec = record(&model, &grid(1.0, 50), swing);
    let (knee, hip) = (model.dof_index("knee").unwrap(), model.dof_index("hip").unwrap());
    let csv = |o: CsvOptions| {
        let (_, bytes) = export_with(&model, &rec, Format::Csv, &Options { csv: o, ..Options::default() }).unwrap();
        csv_rows(&String::from_utf8(bytes).unwrap())
    };
    let joints = vec!["hip".to_string(), "knee".to_string()];
    let picked = CsvOptions { angles: AngleUnit::Radian, columns: vec![Column::Q, Column::Tau], joints, rate: Some(10.0) };
    let (header, rows) = csv(picked.clone());
    // Model order whatever the order asked; the unit in every name.
    assert_eq!(header, ["time_s", "knee.q_rad", "knee.tau_Nm", "hip.q_rad", "hip.tau_Nm"]);
    assert_eq!(rows.len(), 11);
    for (r, row) in rows.iter().enumerate() {
        let t = r as f64 / 10.0;
        assert_close(row[0], t, 1e-9, "time");
        assert_close(row[1], swing(knee, t)[0], 1e-8, "knee q in rad");
        assert_close(row[4], swing(hip, t)[3], 1e-8, "hip torque");
    }
    // Degrees (the default) are the radians × 180/π; the default columns are all four per joint.
    let (header, deg) = csv(CsvOptions { angles: AngleUnit::Degree, columns: Column::ALL.to_vec(), ..picked.clone() });
    assert_eq!(header[1..5], ["knee.q_deg", "knee.qd_deg_s", "knee.qdd_deg_s2", "knee.tau_Nm"]);
    assert_close(deg[3][1], rows[3][1].to_degrees(), 1e-6, "degrees");
    assert!((deg[3][1] - rows[3][1]).abs() > 1e-3);
    // At 30 rows per second the rows fall between the samples: q by the samples' q and q̇.
    let (_, rows) = csv(CsvOptions { rate: Some(30.0), ..picked.clone() });
    assert_eq!(rows.len(), 31);
    for (r, row) in rows.iter().enumerate() {
        assert_close(row[1], swing(knee, r as f64 / 30.0)[0], 1e-5, "knee q at 30 Hz");
    }
    let bad = CsvOptions { joints: vec!["neck".into()], ..picked.clone() };
    let err = export_with(&model, &rec, Format::Csv, &Options { csv: bad, ..Options::default() }).unwrap_err();
    assert!(err.to_string().contains("no joint \"neck\"") && err.to_string().contains("ankle, knee"), "{err}");
    let err = Options::from_names(None, "cm", "joint", "deg", &["q".into(), "torque".into()], vec![], None).unwrap_err();
    assert!(err.to_string().contains("unknown column \"torque\"") && err.to_string().contains("tau"), "{err}");
    let err = Options::from_names(None, "inch", "joint", "deg", &[], vec![], None).unwrap_err();
    assert!(err.to_string().contains("m, cm"), "{err}");
}

// ---- Plots ----

#[test]
fn plots_draw_every_joint_with_the_guess_dashed_and_the_strength_band() {
    let model = one_joint(12.0);
    let mut rec = record(&model, &grid(1.0, 100), |_, t| [t, 1.0, 0.0, 10.0 * (2.0 * PI * t).sin()]);
    rec.contacts = vec![ContactRecord { name: "grip".into(), frame: "forearm".into(), target: [0.0; 3], normal: None }];
    for s in &mut rec.samples {
        s.contact_forces = vec![[0.0, 0.0, 5.0 + s.t]];
    }
    let guess = record(&model, &grid(1.0, 100), |_, t| [0.8 * t, 0.8, 0.0, 14.0 * (2.0 * PI * t).sin()]).samples;
    let files = plots(&model, &rec, Some(&guess)).unwrap();
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    for stem in ["q", "qd", "qdd", "tau", "contact_forces"] {
        assert!(names.contains(&format!("{stem}.svg").as_str()) && names.contains(&format!("{stem}.png").as_str()), "{names:?}");
    }
    for (name, bytes) in &files {
        if name.ends_with(".png") {
            assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{name}");
            let png = resvg::tiny_skia::Pixmap::decode_png(bytes).unwrap();
            assert!(png.width() >= 1000 && png.height() >= 500, "{name}: {}×{}", png.width(), png.height());
        } else {
            let svg = std::str::from_utf8(bytes).unwrap();
            assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"), "{name}");
        }
    }
    let svg = |n: &str| String::from_utf8(files.iter().find(|(name, _)| name == n).unwrap().1.clone()).unwrap();
    let tau = svg("tau.svg");
    assert!(
        tau.contains("elbow (N·m)") && tau.contains("initial guess") && tau.contains("strength limit"),
        "tau.svg lacks a part"
    );
    assert!(tau.contains("opacity=\"0.12\" fill=\"#3CA05A\""), "the strength band is not shaded");
    assert!(svg("q.svg").contains("elbow (°)") && svg("q.svg").contains("angle (°)"));
    assert!(svg("contact_forces.svg").contains("grip (N, world axes)"));

    // Without a guess there is no dashed curve; a limit far beyond the torques is named, not drawn.
    let far = one_joint(500.0);
    let svgs = plot_svgs(&far, &rec, None).unwrap();
    let tau = &svgs.iter().find(|(n, _)| n == "tau.svg").unwrap().1;
    assert!(!tau.contains("initial guess") && tau.contains("off scale") && !tau.contains("opacity=\"0.12\" fill=\"#3CA05A\""));
    assert_eq!(svgs.len(), 5);
}

/// The numbers of an SVG attribute list `points="x,y x,y …"`, as points.
fn svg_points(element: &str) -> Vec<(f64, f64)> {
    let Some(start) = element.find("points=\"") else { return vec![] };
    let list = &element[start + 8..];
    let list = &list[..list.find('"').unwrap()];
    list.split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// Every `<polyline>` of `svg` whose stroke is `colour`, as its points.
fn polylines(svg: &str, colour: &str) -> Vec<Vec<(f64, f64)>> {
    svg.split("<polyline").skip(1).filter(|e| e.contains(&format!("stroke=\"{colour}\""))).map(svg_points).collect()
}

/// The plotting areas of a plotters SVG, `[left, top, right, bottom]`: each panel's y axis (a long vertical
/// black line) and x axis (a long horizontal one below it).
fn plot_areas(svg: &str) -> Vec<[f64; 4]> {
    let axes = polylines(svg, "#000000");
    let vertical = axes.iter().filter(|p| p.len() == 2 && p[0].0 == p[1].0 && (p[0].1 - p[1].1).abs() > 50.0);
    vertical
        .map(|y_axis| {
            let (top, bottom) = (y_axis[0].1.min(y_axis[1].1), y_axis[0].1.max(y_axis[1].1));
            let x_axis = axes
                .iter()
                .find(|p| p.len() == 2 && p[0].1 == p[1].1 && (p[0].1 - bottom).abs() <= 2.0 && p[1].0 - p[0].0 > 100.0)
                .expect("an x axis under the y axis");
            [y_axis[0].0, top, x_axis[1].0, bottom]
        })
        .collect()
}

/// The legend box of a plot: the one rectangle filled with the legend's colour, `[left, top, right, bottom]`.
fn legend_box(svg: &str) -> [f64; 4] {
    let rect = svg.split("<rect").find(|e| e.contains("fill=\"#FAFAF6\"")).expect("a legend box");
    let attr = |name: &str| -> f64 {
        let at = rect.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        rect[at..at + rect[at..].find('"').unwrap()].parse().unwrap()
    };
    [attr("x"), attr("y"), attr("x") + attr("width"), attr("y") + attr("height")]
}

#[test]
fn the_plan_sets_the_torque_scale_and_the_legend_sits_outside_every_panel() {
    // A pendulum-like plan: |τ| ≤ 0.1 N·m, its guess 1000 times larger. Scaled to hold the guess the plan
    // would be a flat line (0.1 % of the axis); scaled to the plan it fills the axis, the guess cut.
    let model = one_joint(1000.0);
    let rec = record(&model, &grid(1.0, 100), |_, t| [t, 1.0, 0.0, 0.1 * (2.0 * PI * t).sin()]);
    let guess = record(&model, &grid(1.0, 100), |_, t| [t, 1.0, 0.0, 100.0 * (2.0 * PI * t).sin()]).samples;
    let svgs = plot_svgs(&model, &rec, Some(&guess)).unwrap();
    let tau = &svgs.iter().find(|(n, _)| n == "tau.svg").unwrap().1;
    let [area] = plot_areas(tau)[..] else { panic!("one panel expected") };
    let planned: Vec<(f64, f64)> = polylines(tau, "#1F5AAA").concat();
    let span = |pts: &[(f64, f64)]| {
        pts.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max) - pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min)
    };
    let share = span(&planned) / (area[3] - area[1]);
    assert!(share > 0.8, "the plan spans {:.0} % of the axis height", 100.0 * share);
    // The guess is drawn, cut to the axis, and the caption and legend say so.
    // The legend box lies above the panel: it shares no pixel with the plotting area.
    let legend = legend_box(tau);
    assert!(legend[3] < area[1], "legend {legend:?} overlaps the plot area {area:?}");
    let dashed: Vec<(f64, f64)> = polylines(tau, "#C84628").concat().into_iter().filter(|p| p.1 > legend[3]).collect();
    assert!(dashed.len() > 10 && dashed.iter().all(|p| p.1 >= area[1] - 1.0 && p.1 <= area[3] + 1.0), "{dashed:?}");
    assert!(tau.contains("guess cut at the plan") && tau.contains("cut where it leaves the plan"));

    // Twelve joints: every panel's plotting area is clear of the legend, and every axis is labelled with units.
    let many = human_model(Structure::Sagittal);
    let rec = record(&many, &grid(1.0, 50), swing);
    for (name, svg) in plot_svgs(&many, &rec, Some(&rec.samples.clone())).unwrap() {
        let (areas, legend) = (plot_areas(&svg), legend_box(&svg));
        assert_eq!(areas.len(), many.nv(), "{name}");
        assert!(areas.iter().all(|a| legend[3] < a[1] || legend[1] > a[3]), "{name}: the legend overlaps a panel");
        let axis = ["angle (°)", "angular velocity (°/s)", "angular acceleration (°/s²)", "torque (N·m)"];
        assert!(axis.iter().any(|a| svg.matches(a).count() == many.nv()), "{name} lacks a unit on an axis");
        assert_eq!(svg.matches("time (s)").count(), many.nv(), "{name}");
    }
    // A prismatic joint's panels are in metres and newtons, beside the revolute ones in degrees and N·m.
    let mixed = tilted_and_sliding();
    let rec = record(&mixed, &grid(1.0, 20), swing);
    let svgs = plot_svgs(&mixed, &rec, None).unwrap();
    let tau = &svgs.iter().find(|(n, _)| n == "tau.svg").unwrap().1;
    assert!(tau.contains("force (N)") && tau.matches("torque (N·m)").count() == 2 && !tau.contains("N·m or N"));
}

// ---- Bad input ----

#[test]
fn a_directory_without_a_plan_is_refused_with_a_hint() {
    let dir = scratch("empty");
    let err = load_plan_dir(&dir).unwrap_err().to_string();
    assert!(err.contains("holds no plan") && err.contains("mintorque plan"), "{err}");
}

#[test]
fn an_unknown_format_lists_the_known_ones() {
    let err = Format::from_name("fbx").unwrap_err().to_string();
    assert!(err.contains("unknown format \"fbx\"") && err.contains("bvh, gltf, mot, csv"), "{err}");
    for f in Format::ALL {
        assert_eq!(Format::from_name(&f.name().to_uppercase()).unwrap(), f);
    }
}

#[test]
fn records_that_do_not_fit_the_model_are_refused() {
    let model = one_joint(10.0);
    let mut rec = record(&model, &grid(1.0, 4), |_, _| [0.0; 4]);
    rec.samples[2].q.push(1.0);
    for f in Format::ALL {
        let err = export(&model, &rec, f).unwrap_err().to_string();
        assert!(err.contains("samples[2]"), "{f}: {err}");
    }
    assert!(plots(&model, &rec, None).is_err());
    assert!(ergonomics(&model, &rec, &BTreeMap::new()).is_err());
    rec.samples.clear();
    let err = export(&model, &rec, Format::Gltf).unwrap_err().to_string();
    assert!(err.contains("no samples"), "{err}");
}

#[test]
fn a_joint_with_direction_limits_is_measured_against_the_limit_of_each_direction() {
    // τ = 10 sin(2πt): against +8 N·m flexing and 4 N·m extending, the share peaks at 10/4 (extension), and
    // the time beyond is the time above +8 plus the time below −4 (each half-wave's crossings, exact).
    let mut model = one_joint(6.0);
    let rec = record(&model, &grid(1.0, 1000), |_, t| [0.1 * t, 0.1, 0.0, 10.0 * (2.0 * PI * t).sin()]);
    model.joints[1].limits.effort_positive = Some(8.0);
    model.joints[1].limits.effort_negative = Some(4.0);
    let e = ergonomics(&model, &rec, &BTreeMap::new()).unwrap();
    let j = &e.joints[0];
    assert_eq!((j.strength_limit_positive, j.strength_limit_negative), (Some(8.0), Some(4.0)));
    assert_close(j.peak_fraction_of_limit.unwrap(), 10.0 / 4.0, 1e-3, "share of the extension limit");
    let beyond = |r: f64| 0.5 - 2.0 * r.asin() / (2.0 * PI);
    assert_close(j.time_above_limit_s, beyond(0.8) + beyond(0.4), 2e-5, "time beyond either limit");
    let table = text_table(&e);
    assert!(table.contains("−4.0/+8.0 N·m"), "{table}");
}
