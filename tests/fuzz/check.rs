//! The invariant every fuzzed input must meet: a clear error naming the file, or success with finite,
//! consistent outputs — never a panic, a hang past a bound, or a non-finite number.

use mintorque::dynamics::batch::StatesFile;
use mintorque::model::{figure, Model};
use std::sync::mpsc;
use std::time::Duration;

/// How long one parse may take before it counts as a hang.
pub const PARSE_BOUND: Duration = Duration::from_secs(10);
/// How long one short plan (1 s time limit) may take, its sampling and rendering included.
pub const PLAN_BOUND: Duration = Duration::from_secs(20);

/// Runs `case` on its own thread: its answer, or a failure saying it panicked or passed `bound`.
pub fn guarded(bound: Duration, case: impl FnOnce() -> Result<(), String> + Send + 'static) -> Result<(), String> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(case());
    });
    match rx.recv_timeout(bound) {
        Ok(answer) => answer,
        Err(mpsc::RecvTimeoutError::Timeout) => Err(format!("hang: no answer within {bound:?}")),
        Err(mpsc::RecvTimeoutError::Disconnected) => Err("panic (its message is above)".into()),
    }
}

/// An error is clear when it names the file it was given.
pub fn names_file(message: &str, origin: &str) -> Result<(), String> {
    match message.contains(origin) {
        true => Ok(()),
        false => Err(format!("the error does not name {origin}: {message}")),
    }
}

/// A model read without error: its numbers finite, its dynamics finite at a few states within its limits,
/// and written as a figure file it reads back the same joints.
pub fn model_is_sound(model: &Model, origin: &str) -> Result<(), String> {
    let finite = |x: &[f64]| x.iter().all(|v| v.is_finite());
    for (j, b) in model.joints.iter().zip(&model.bodies).skip(1) {
        let p = &j.placement;
        let numbers = [p.rotation.as_slice(), p.translation.as_slice(), j.axis.as_slice(), &[b.inertia.mass]].concat();
        if !finite(&numbers) || j.limits.lower > j.limits.upper {
            return Err(format!("{origin}: joint {:?} read with non-finite or inconsistent numbers: {j:?}", j.name));
        }
    }
    let again = figure::parse(&figure::to_toml(model), "round-trip.figure.toml").map_err(|e| format!("round trip: {e}"))?;
    if again.joint_names() != model.joint_names() {
        return Err(format!("round trip changed the joints: {:?} vs {:?}", again.joint_names(), model.joint_names()));
    }
    dynamics_are_finite(model)
}

/// τ, its derivatives, H and forward dynamics at rest, and at the middle of the limits moving, are finite.
fn dynamics_are_finite(model: &Model) -> Result<(), String> {
    let names = model.joint_names();
    let joints: Vec<String> = names.iter().map(|n| format!("{{\"name\": {n:?}}}")).collect();
    let mid: Vec<String> = model.joints[1..]
        .iter()
        .map(|j| match (j.limits.lower.is_finite(), j.limits.upper.is_finite()) {
            (true, true) => format!("{}", 0.5 * (j.limits.lower + j.limits.upper)),
            _ => "0.3".into(),
        })
        .collect();
    let ones = vec!["1.0"; names.len()].join(", ");
    let zeros = vec!["0"; names.len()].join(", ");
    let text = format!(
        "{{\"joints\": [{}], \"states\": [{{\"q\": [{zeros}], \"v\": [{zeros}], \"a\": [{zeros}], \"tau_rand\": [{zeros}]}}, \
         {{\"q\": [{}], \"v\": [{ones}], \"a\": [{ones}], \"tau_rand\": [{ones}]}}]}}",
        joints.join(", "),
        mid.join(", ")
    );
    let states = StatesFile::parse(&text, "fuzz-states.json", model).map_err(|e| format!("states of the model: {e}"))?;
    states.evaluate(model, &model.gravity).map(|_| ()).map_err(|e| format!("dynamics of a model read without error: {e}"))
}
