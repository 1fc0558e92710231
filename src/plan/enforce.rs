//! Refinement until the limits hold between the nodes ([`super::between`]): check the solved motion on the
//! dense grid; where a row group misses its tolerance, add check nodes at the worst time of every
//! offending knot span, and of every span where that group is over its bound by less than its tolerance or
//! under it by less than ten tolerances ([`between::check_near`]; inequality rows at weight 0 in the
//! objective, the position limits alone for a missed position limit, or loop closures) and re-solve from
//! the previous solution, warm-started with its multipliers (the new rows' start at 0), with at most the
//! first solve's iterations — and where that does not converge, from the initial guess `guess`, cold (the
//! bundled examples converge so where the warm re-solve crawls, docs/task-file.md). Repeat until the check
//! holds, or the rounds ([`super::BetweenNodes::rounds`]), the iterations or the time of the whole solve are
//! spent; then the plan is not converged, and the reason names every missed limit in its units. Where the
//! check holds at once this costs one dense evaluation.

use super::between::{self, CheckNodes, NodeViolation};
use super::run::{remaining, run_start, Run};
use super::transcription::samples::within_span;
use super::transcription::RowKind;
use super::{SolverKind, Spec, Transcription};
use crate::error::Result;
use crate::solve::{Multipliers, Outcome, Progress, Settings, StopReason};
use std::time::Instant;

/// A warm re-solve whose scaled violation grows past this multiple of its start's has diverged
/// ([`Settings::warm_divergence`]). 10, not 100: the push-up at N = 31 walked its warm re-solve from 8.2e-3
/// to 0.46 and wandered there for 1525 steps under the 100× bound before the cold re-solve (3422 → 2037
/// iterations in all); over 35 tasks only two others move, to fewer steps and the same efforts.
const WARM_DIVERGENCE: f64 = 10.0;

/// The result of [`enforce`].
pub(super) struct Enforced {
    /// The last solve (its iterations and evaluations summed over the rounds).
    pub run: Run,
    /// The spec with the check nodes added.
    pub spec: Spec,
    /// What still misses its tolerance between the nodes (empty: the check holds).
    pub violations: Vec<NodeViolation>,
    /// Rounds of refinement made.
    pub rounds: usize,
}

/// Checks `run` (solved from `guess`) between the nodes and refines as the module docs say, within
/// `settings.max_iterations` (counted over the whole solve, `run`'s included) and `deadline`.
pub(super) fn enforce(
    spec: &Spec,
    solver: SolverKind,
    settings: &Settings,
    deadline: Option<Instant>,
    mut run: Run,
    guess: &[f64],
    observer: &mut dyn FnMut(&Progress),
) -> Result<Enforced> {
    let b = spec.between_nodes;
    let mut spec = spec.clone();
    let mut rounds = 0;
    let first_iterations = run.outcome.iterations;
    loop {
        let (violations, near) = between::check_near(&spec, &run.outcome.x, b.per_span, &b.tolerances)?;
        if violations.is_empty() {
            return Ok(Enforced { run, spec, violations, rounds });
        }
        let more = more_nodes(violations.iter().chain(&near), &spec.check_nodes, &spec)?;
        let left = settings.max_iterations.saturating_sub(run.outcome.iterations);
        let why = if !run.outcome.converged {
            None // the solve itself did not converge: its own reason stands
        } else if !b.refine {
            Some("refinement between the nodes is off".to_string())
        } else if rounds >= b.rounds || left == 0 || remaining(deadline).is_some_and(|t| t <= 0.0) || more.is_empty() {
            Some(format!(
                "after {rounds} round(s) of refinement ({} check nodes added){}",
                spec.check_nodes.len(),
                root_hint(&violations, spec.n_ctrl)
            ))
        } else {
            let warm = carried(&run.outcome.multipliers, &spec, &more)?;
            spec.check_nodes.extend(&more);
            // Warm first, with at most the first solve's iterations; where that does not converge (the
            // augmented Lagrangian can crawl at the penalty it ended with), solve again from the guess,
            // cold, with the check nodes — within what is left of the one budget.
            let cap = left.min(first_iterations.max(100));
            // A warm re-solve that goes astray is abandoned for the cold one at the step its violation
            // passes 10× its start (the twist lift's did, twice, within 15 steps, with multipliers grown
            // large against its nearly straight legs' closure).
            let warm = Settings {
                warm_start: Some(warm),
                warm_divergence: Some(WARM_DIVERGENCE),
                max_iterations: cap,
                ..settings.clone()
            };
            let mut next = run_start(&spec, solver, &warm, deadline, &run.outcome.x, observer)?;
            let rest = left.saturating_sub(next.outcome.iterations);
            if !next.outcome.converged && rest > 0 && remaining(deadline).is_none_or(|t| t > 0.0) {
                let cold = Settings { max_iterations: rest, ..settings.clone() };
                next = sum(next, run_start(&spec, solver, &cold, deadline, guess, observer)?);
            }
            run = sum(run, next);
            rounds += 1;
            continue;
        };
        if let Some(why) = why {
            not_converged(&mut run.outcome, &violations, &why);
        }
        return Ok(Enforced { run, spec, violations, rounds });
    }
}

/// What to do when a free root's momenta are missed between their collocation nodes: check nodes cannot
/// hold them (`between::more_nodes`), a finer spline can.
fn root_hint(violations: &[NodeViolation], n_ctrl: usize) -> String {
    if violations.iter().any(|v| {
        matches!(v.kind, crate::plan::transcription::RowKind::RootMomentum | crate::plan::transcription::RowKind::RootForce)
    }) {
        format!("; the free root's momenta (or forces) between its collocation nodes fall with more control points: raise discretization.control_points from {n_ctrl}")
    } else {
        String::new()
    }
}

/// `outcome` marked not converged: the limits missed between the nodes, in units.
fn not_converged(outcome: &mut Outcome, violations: &[NodeViolation], why: &str) {
    const SHOWN: usize = 3;
    let mut listed: Vec<String> = violations.iter().take(SHOWN).map(|v| v.to_string()).collect();
    if violations.len() > SHOWN {
        listed.push(format!("and {} more", violations.len() - SHOWN));
    }
    outcome.converged = false;
    outcome.reason = StopReason::BetweenNodes(format!("{} ({why})", listed.join("; ")));
}

/// Position samples added in every knot span where a position limit is missed, besides its worst time
/// ([`super::transcription::samples::within_span`]): a joint that rides its limit across the span is held there
/// in one round, instead of going over at another time of the span after the re-solve. 35 tasks, one start,
/// against the worst time alone: 2130 → 2103 iterations (`dip_down_space` 127 → 117, the 36-DOF wave-step
/// 141 → 124 and crouch 193 → 183, none more than 4 up), efforts within 0.02 %, the first solves the same;
/// with 3 a span the wave-step took 148, with 4 2102 in all, with 10 the crouch's effort rose 0.01 %.
const POSITION_SAMPLES_PER_MISSED_SPAN: usize = 6;

/// The check nodes to add for `violations`: the worst time of every offending knot span, split into
/// closure, position and limit nodes, without times already in `nodes` (a position limit's time not where a
/// limit node imposes it already), nor the motion's ends, where every inequality row holds at its end nodes
/// already (a near span's worst time is often an end, held still on its posture); a missed position limit's
/// spans get [`POSITION_SAMPLES_PER_MISSED_SPAN`] more position checks.
fn more_nodes<'a>(
    violations: impl IntoIterator<Item = &'a NodeViolation>,
    nodes: &CheckNodes,
    spec: &Spec,
) -> Result<CheckNodes> {
    let mut more = CheckNodes::default();
    let end = |t: f64| t.min(spec.duration - t) <= 1e-9 * spec.duration;
    // A free root's momenta hold at their collocation nodes only (more rows would over-determine its spline):
    // check nodes do not help them, more control points do.
    for v in violations.into_iter().filter(|v| !matches!(v.kind, RowKind::RootMomentum | RowKind::RootForce)) {
        for &(_, t, _) in v.spans.iter().filter(|s| v.kind == RowKind::Closure || !end(s.1)) {
            let (have, list) = match v.kind {
                RowKind::Closure => (&nodes.closures, &mut more.closures),
                RowKind::AngleLimit | RowKind::SlideLimit => (&nodes.positions, &mut more.positions),
                _ => (&nodes.limits, &mut more.limits),
            };
            if !have.iter().chain(list.iter()).any(|s| (s - t).abs() < 1e-12) {
                list.push(t);
            }
        }
    }
    let samples = span_samples(&more.positions, nodes, spec)?;
    more.positions.extend(samples.into_iter().filter(|&t| !end(t)));
    // A full node imposes the position limits too.
    let full: Vec<f64> = nodes.limits.iter().chain(&more.limits).copied().collect();
    more.positions.retain(|t| !full.iter().any(|s| (s - t).abs() < 1e-12));
    Ok(more)
}

/// The position samples of every knot span with a position check in `added`, but those within a twentieth
/// of a span of a position check made (`nodes`) or added.
fn span_samples(added: &[f64], nodes: &CheckNodes, spec: &Spec) -> Result<Vec<f64>> {
    let spans = spec.n_ctrl - 3;
    let h = spec.duration / spans as f64;
    let within = within_span(spec, POSITION_SAMPLES_PER_MISSED_SPAN)?;
    let mut samples: Vec<f64> = Vec::new();
    for &t in added {
        let span = ((t / h) as usize).min(spans - 1);
        for s in within.iter().map(|r| (span as f64 + r) * h) {
            if !nodes.positions.iter().chain(added).chain(&samples).any(|p| (p - s).abs() < 0.05 * h) {
                samples.push(s);
            }
        }
    }
    Ok(samples)
}

/// The multipliers of `spec`'s transcription carried to its rows with the check nodes `more` added
/// ([`Transcription::carried_multipliers`]).
fn carried(multipliers: &Multipliers, spec: &Spec, more: &CheckNodes) -> Result<Multipliers> {
    let mut grown = spec.clone();
    grown.check_nodes.extend(more);
    Ok(Transcription::new(&grown)?.carried_multipliers(more, multipliers))
}

/// Two solves in a row as one: the second's result, both's counts.
fn sum(first: Run, second: Run) -> Run {
    let (a, b) = (&first.outcome, second.outcome);
    let outcome = Outcome {
        iterations: a.iterations + b.iterations,
        evaluations: a.evaluations + b.evaluations,
        outer_iterations: a.outer_iterations + b.outer_iterations,
        ..b
    };
    Run {
        outcome,
        polished: first.polished || second.polished,
        seconds: first.seconds + second.seconds,
        polish_skipped: first.polish_skipped,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::initial_x;

    /// Where a limit is missed in one knot span, its spans that hold within a few tolerances of the bound are
    /// near too (the next re-solve tends to push them over). The pendulum's linear guess rises from −70° to 70°;
    /// with its upper limit set anywhere from 60° to 69.5°, the limit is missed at the end, every span listed
    /// near is at most 1° (10 tolerances) below it, and for some of these limits a span that holds is listed.
    #[test]
    fn spans_close_below_a_missed_limit_are_near() {
        let task = crate::plan::examples::load("pendulum");
        let mut held_but_near = 0;
        for k in 0..20 {
            let mut spec = task.spec.clone();
            spec.model.joints[1].limits.upper = (60.0 + 0.5 * k as f64).to_radians();
            let x = initial_x(&spec, &mut Transcription::new(&spec).unwrap()).unwrap();
            let b = spec.between_nodes;
            let (missed, near) = between::check_near(&spec, &x, b.per_span, &b.tolerances).unwrap();
            assert!(missed.iter().any(|v| v.constraint.contains("upper")), "{missed:?}");
            let spans: Vec<_> = near.iter().flat_map(|v| &v.spans).collect();
            assert!(spans.iter().all(|s| s.2 > -1.0 - 1e-9), "{spans:?}");
            held_but_near += spans.iter().filter(|s| s.2 < 0.0).count();
        }
        assert!(held_but_near > 0, "no span that holds close below the limit was listed near");
    }

    /// A missed position limit gets a position check (its rows alone) and the samples of its knot span, any
    /// other limit a whole check node, a closure a closure node; a time at either end of the motion, whose end
    /// nodes hold every row already, or where a whole check node is already, gets none.
    #[test]
    fn position_limits_get_position_checks_and_the_ends_none() {
        let spec = crate::plan::examples::load("pendulum").spec;
        let (d, spans) = (spec.duration, spec.n_ctrl - 3);
        let h = d / spans as f64;
        let missed = |kind, times: &[f64]| NodeViolation {
            constraint: String::new(),
            time_s: times[0],
            value: 0.0,
            limit: 0.0,
            excess: 1.0,
            tolerance: 0.1,
            unit: String::new(),
            kind,
            spans: times.iter().map(|&t| (((t / h) as usize).min(spans - 1), t, 1.0)).collect(),
        };
        let violations = [
            missed(RowKind::AngleLimit, &[0.0, 0.3 * d, 0.61 * d, d]),
            missed(RowKind::Torque, &[0.8 * d, d]),
            missed(RowKind::Closure, &[0.0, 0.5 * d]),
            missed(RowKind::SlideLimit, &[0.8 * d, 0.95 * d]),
        ];
        let have = CheckNodes { limits: vec![], closures: vec![], positions: vec![0.3 * d] };
        let more = more_nodes(&violations, &have, &spec).unwrap();
        assert_eq!((more.limits.clone(), more.closures.clone()), (vec![0.8 * d], vec![0.0, 0.5 * d]));
        // The worst times first, then the samples of their spans (the slide's at 0.8 d too, where the torque's
        // whole node imposes its limit at that time), none at an end or on a check made.
        assert_eq!(more.positions[..2], [0.61 * d, 0.95 * d]);
        // Each in the span of one of them (its knot counted in: [s h, (s + 1) h)).
        let in_span = |t: f64, of: f64| {
            let s = ((of / h) as usize).min(spans - 1) as f64;
            t >= s * h - 1e-9 * h && t < (s + 1.0) * h
        };
        let samples = &more.positions[2..];
        assert!(samples.len() >= 8, "{samples:?}");
        assert!(samples.iter().all(|&t| t > 0.0 && t < d && [0.61, 0.8, 0.95].iter().any(|f| in_span(t, f * d))), "{samples:?}");
        assert!(samples.iter().all(|&t| (t - 0.61 * d).abs() >= 0.05 * h && (t - 0.95 * d).abs() >= 0.05 * h));
    }
}
