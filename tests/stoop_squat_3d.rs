//! The stoop and squat lifts on the 3D whole body (`examples/lift_stoop_3d.toml`, `lift_squat_3d.toml`;
//! issue 11): the same 15 kg box taken up from the same place to the waist, knees straight or bent, the box
//! (too wide to fit between the knees) kept in front of the legs. Each claim compares the two plans and
//! fails when the motions are swapped: the squat's knees work as extensors where the stoop's hold as
//! flexors, and the squat, holding the box further out in front of its knees, loads L5/S1 more (Kingma,
//! Bosch, Bruins & van Dieën 2004, *Ergonomics* 47:1365). Both plans are also checked to be lifts a person
//! makes: a stoop stays a stoop, the box clears the legs, both feet carry the load, and the body stays in
//! its sagittal plane. The hips' peaks are printed, with no order asserted (docs/ergonomic-examples.md says why).

use mintorque::dynamics::{kinematics, Data};
use mintorque::plan::{self, task::Task};
use mintorque::report::ergonomics::{self, loads, Setup};
use mintorque::report::record::PlanRecord;
use mintorque::Model;
use std::path::Path;

struct Lift {
    record: PlanRecord,
    e: ergonomics::Ergonomics,
    model: Model,
}

/// `examples/NAME.toml` planned (converged), sampled at 100 Hz, with its ergonomic measures.
fn measured(name: &str) -> Lift {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(format!("{name}.toml"));
    let mut task = Task::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let planned = task.plan(&mut |_| {}).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(planned.converged(), "{name}: {}", planned.outcome.reason);
    eprintln!("{name}: {} iterations, {:.2} s of solving", planned.outcome.iterations, planned.solve_seconds);
    let spec = &task.spec;
    let samples = plan::sample(spec, &planned, &mintorque::report::sample_times(spec.duration, 100.0)).unwrap();
    let record = PlanRecord::new(spec, &planned, &samples);
    let origin = path.display().to_string();
    let setup = Setup::resolve(&task.file, spec, &origin).unwrap();
    let series = loads::series(&spec.model, &record, &spec.loads).unwrap();
    let mut e = ergonomics::ergonomics(&spec.model, &record, &Default::default()).unwrap();
    e.add_measures(&spec.model, &record, &setup, &series, &origin).unwrap();
    Lift { record, e, model: spec.model.clone() }
}

impl Lift {
    /// The peak of `−τ` (N·m) over both sides' `knee` or `hip_y`: the extensors' torque (+q is flexion).
    fn peak_extension(&self, joint: &str) -> f64 {
        let dofs = ["l_", "r_"].map(|s| self.model.dof_index(&format!("{s}{joint}")).unwrap());
        self.record.samples.iter().flat_map(|s| dofs.map(|i| -s.tau[i])).fold(f64::MIN, f64::max)
    }
    /// The largest |q| (degrees) of the DOF `name` over the lift.
    fn widest(&self, name: &str) -> f64 {
        let i = self.model.dof_index(name).unwrap();
        self.record.samples.iter().map(|s| s.q[i].to_degrees().abs()).fold(0.0, f64::max)
    }
}

/// The box's least clearance from the legs over the lift (m; negative: it cuts into them). The box, 0.30 m
/// deep and tall and held level between the palms (`l_hand`, `r_hand`), is wider (0.4 m) than the legs
/// (the hips 0.19 m apart, the thighs 0.18 m thick), so it must pass in front of them: against points
/// along each thigh (hip → knee) and shank (knee → ankle), the gap `max(|Δx|, |Δz|) − 0.15 − r` with `r`
/// the segment's radius (Table I, 9.5 and 7.0 cm at 1.83 m, scaled by stature).
fn box_clearance(l: &Lift, stature: f64) -> (f64, f64) {
    let m = &l.model;
    let frame = |name: &str| m.frames.iter().position(|f| f.name == name).unwrap();
    let joint = |name: &str| m.dof_index(name).unwrap() + 1;
    let (hands, ankles) = ([frame("l_hand"), frame("r_hand")], [frame("l_ankle"), frame("r_ankle")]);
    let (knees, hips) = ([joint("l_knee"), joint("r_knee")], [joint("l_hip_y"), joint("r_hip_y")]);
    let radii = [0.095, 0.070].map(|r| r * stature / 1.83);
    let mut data = Data::new(m);
    let mut least = (f64::MAX, 0.0);
    for s in &l.record.samples {
        kinematics::placements(m, &mut data, &s.q);
        let at = |f: usize| kinematics::frame_placement(m, &data, f).translation;
        let c = (at(hands[0]) + at(hands[1])) / 2.0;
        for side in 0..2 {
            let (hip, knee, ankle) = (data.oMi[hips[side]].translation, data.oMi[knees[side]].translation, at(ankles[side]));
            for ((a, b), r) in [(hip, knee), (knee, ankle)].into_iter().zip(radii) {
                for k in 0..=10 {
                    let p = a + (b - a) * (k as f64 / 10.0);
                    let gap = (p.x - c.x).abs().max((p.z - c.z).abs()) - 0.15 - r;
                    if gap < least.0 {
                        least = (gap, s.t);
                    }
                }
            }
        }
    }
    least
}

#[test]
fn a_squat_lift_works_the_knees_and_with_the_box_in_front_of_them_loads_the_back_more_than_a_stoop() {
    let (stoop, squat) = (measured("lift_stoop_3d"), measured("lift_squat_3d"));
    let failures: Vec<String> =
        [("stoop", &stoop), ("squat", &squat)].iter().flat_map(|(n, l)| lifts_a_person_makes(n, l)).collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    the_box_starts_at_one_place(&stoop, &squat);
    only_the_squat_works_its_knee_extensors(&stoop, &squat);
    eprintln!("peak hip extension: stoop {:.1}, squat {:.1} N·m", stoop.peak_extension("hip_y"), squat.peak_extension("hip_y"));
    the_squat_loads_the_back_more(&stoop, &squat);
}

/// The same box place: H within 2 cm, V within 5 cm, so the lifting equation (which sees where the load is,
/// not the posture) gives both origins the same recommended weight limit, within 5 %.
fn the_box_starts_at_one_place(stoop: &Lift, squat: &Lift) {
    let (a, b) = (stoop.e.lifting_equation.as_ref().unwrap(), squat.e.lifting_equation.as_ref().unwrap());
    let (la, lb) = (&a.origin.location, &b.origin.location);
    let (ra, rb) = (a.origin.multipliers.rwl_kg, b.origin.multipliers.rwl_kg);
    eprintln!(
        "origin: stoop H {:.1} V {:.1} cm, RWL {ra:.2} kg; squat H {:.1} V {:.1} cm, RWL {rb:.2} kg; LI {:.2} / {:.2}",
        la.horizontal_cm, la.vertical_cm, lb.horizontal_cm, lb.vertical_cm, a.lifting_index, b.lifting_index
    );
    assert!((la.horizontal_cm - lb.horizontal_cm).abs() < 2.0 && (la.vertical_cm - lb.vertical_cm).abs() < 5.0);
    assert!((ra - rb).abs() < 0.05 * ra, "RWL {ra} vs {rb} kg");
}

/// A stoop keeps its knees nearly straight, the squat starts deep. At the held start the squat's bent knees
/// push as extensors (τ < 0: the body's weight acts behind them), the stoop's straight knees hold as flexors
/// (τ > 0: the hips back, the weight in front of the knee line); over the lift only the squat's knee
/// extensors work.
fn only_the_squat_works_its_knee_extensors(stoop: &Lift, squat: &Lift) {
    let knees = |l: &Lift| l.widest("l_knee").max(l.widest("r_knee"));
    assert!(knees(stoop) < 20.0 && knees(squat) > 60.0, "knees: stoop ≤ {}°, squat ≤ {}°", knees(stoop), knees(squat));
    let knee = stoop.model.dof_index("l_knee").unwrap();
    let (start_stoop, start_squat) = (stoop.record.samples[0].tau[knee], squat.record.samples[0].tau[knee]);
    let (ext_stoop, ext_squat) = (stoop.peak_extension("knee"), squat.peak_extension("knee"));
    eprintln!("knee τ at the start: stoop {start_stoop:.1}, squat {start_squat:.1} N·m; peak extension: stoop {ext_stoop:.1}, squat {ext_squat:.1} N·m");
    assert!(start_squat < 0.0 && start_stoop > 20.0, "knee τ at the start: squat {start_squat}, stoop {start_stoop} N·m");
    assert!(ext_squat > 15.0 && ext_stoop < 0.2 * ext_squat, "knee extension: squat {ext_squat}, stoop {ext_stoop} N·m");
}

/// Both lifts load L5/S1 above NIOSH's 3400 N action limit in the first half, where the trunk is bent over
/// the box. With the box in front of the knees the squat holds it further from L5/S1 and loads the back
/// more: peak compression more than 5 % above the stoop's, and a higher extensor moment (Kingma et al. 2004:
/// from 5 cm with the feet behind the box, squat lifting +17 % compression and +20 % net moment).
fn the_squat_loads_the_back_more(stoop: &Lift, squat: &Lift) {
    let (bs, bq) = (stoop.e.low_back.clone().unwrap(), squat.e.low_back.clone().unwrap());
    eprintln!(
        "L5/S1: stoop {:.0} N at {:.2} s ({:.0} N·m), squat {:.0} N at {:.2} s ({:.0} N·m)",
        bs.peak_compression_n,
        bs.peak_compression_time_s,
        bs.peak_extensor_moment_nm,
        bq.peak_compression_n,
        bq.peak_compression_time_s,
        bq.peak_extensor_moment_nm
    );
    for b in [&bs, &bq] {
        let (c, t) = (b.peak_compression_n, b.peak_compression_time_s);
        assert!(c > 3400.0 && t < 1.0, "peak compression {c} N at {t} s");
    }
    let (cs, cq) = (bs.peak_compression_n, bq.peak_compression_n);
    assert!(cq > 1.05 * cs, "compression: squat {cq}, stoop {cs} N");
    let (ms, mq) = (bs.peak_extensor_moment_nm, bq.peak_extensor_moment_nm);
    assert!(mq > ms, "extensor moment: squat {mq}, stoop {ms} N·m");
}

/// What every plan of a two-footed lift must show: the box clear of the legs, the right foot (held by
/// contacts, the left is the root) carrying a fair share of the weight, and a symmetric lift staying in
/// its sagittal plane (the lateral bends and turns of hips and spine under 5°: the left foot is the root
/// and the right is held by two points, so the task is not exactly symmetric).
/// Returns what fails.
fn lifts_a_person_makes(name: &str, l: &Lift) -> Vec<String> {
    let (clearance, at) = box_clearance(l, 1.75);
    let weight = (l.model.bodies.iter().map(|b| b.inertia.mass).sum::<f64>()) * 9.81;
    let share = |s: &mintorque::report::record::SampleRecord| s.contact_forces.iter().map(|f| f[2]).sum::<f64>() / weight;
    let (least, most) = l.record.samples.iter().map(share).fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    let lateral = ["l_hip_x", "r_hip_x", "l_hip_z", "r_hip_z", "lumbar_x", "lumbar_z", "thoracic_x", "thoracic_z"];
    let widest = lateral.iter().map(|j| l.widest(j)).fold(0.0, f64::max);
    eprintln!("{name}: box clears the legs by {:.1} mm at least (at {at:.2} s); right foot {:.0}–{:.0} % of the weight; lateral ≤ {widest:.2}°", clearance * 1e3, least * 100.0, most * 100.0);
    let mut failures = Vec::new();
    if clearance < -0.01 {
        failures.push(format!("{name}: the box cuts {:.0} mm into the legs at {at:.2} s", -clearance * 1e3));
    }
    if least < 0.3 || most > 0.7 {
        failures.push(format!("{name}: the right foot carries {least:.2}–{most:.2} of the weight"));
    }
    if widest > 5.0 {
        failures.push(format!("{name}: the lift leaves its sagittal plane by {widest:.1}°"));
    }
    failures
}
