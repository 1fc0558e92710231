//! The rounds of starts on the threads ([`run_rounds`]). Which starts are used and which are polished is
//! decided round by round as [`super`]'s module docs say, from the starts' results alone; the threads only
//! choose *when* each piece runs:
//! - a start whose first phase did not stall — and the first start, which is never left unpolished — is
//!   finished at once, without waiting for the rest of its round;
//! - a stalled start waits for its round's decision ([`HOPELESS`]), then its polish runs on any thread;
//! - a thread with nothing of the current round left to do begins the next round's first phases ahead of
//!   time (they depend on no other start); if the round ends the solve, they are stopped ([`Cancel`]) and
//!   dropped;
//! - the first start, once converged, is checked between the nodes (and re-solved with check nodes where it
//!   misses a limit there) on the caller's thread at once, while the other threads go on with the other
//!   starts: the plan keeps the first start on most tasks (28 of the 35 of docs/performance.md), and its
//!   check then no longer waits for the slowest start of the last round. It is stopped and dropped as soon
//!   as another start has converged to less effort (beyond [`TIE`]: the plan cannot keep the first start
//!   then); where it is not kept, the kept start is checked after the rounds, as before.
//!
//! So the plan is the one the rounds make one after another, on any number of threads, while a fast start
//! no longer leaves its thread idle until the slow one of its round ends.

use super::{HOPELESS, TIE};
use crate::error::{Error, Result};
use crate::plan::run::{Run, Started};
use crate::solve::{Cancel, Progress};
use std::sync::{Condvar, Mutex, MutexGuard};

/// Where a start is.
enum Slot<'s> {
    /// Its first phase not begun.
    Waiting,
    /// A thread runs its first phase (and, where that did not stall, its finish), or its polish.
    Running,
    /// Its first phase stalled: the polish waits for its round's decision.
    Stalled(Started<'s>),
    /// Decided: to be finished, polished unless the reason says why not.
    Ready(Started<'s>, Option<String>),
    /// Its first phase failed.
    Failed(Error),
    /// Finished.
    Done(Run),
}

/// A piece of work for a thread.
enum Job<'s> {
    First(usize),
    Finish(usize, Box<Started<'s>>, Option<String>),
}

/// The starts and the rounds decided so far.
struct State<'s> {
    slots: Vec<Slot<'s>>,
    /// Starts `[0, decided)` are in rounds whose polishes are decided.
    decided: usize,
    /// Once the rounds have ended: how many starts they used, or the first failure of a used one.
    end: Option<Result<usize>>,
    /// One flag per start (children of the caller's): a start begun ahead of time and not needed is stopped.
    cancels: Vec<Cancel>,
    /// The first start's check (a child of the caller's flag), stopped once another start has done better.
    check_cancel: Cancel,
    /// A job's panic, raised again once every thread has stopped.
    panicked: Option<Box<dyn std::any::Any + Send>>,
}

impl<'s> State<'s> {
    /// The next job, claimed: a decided polish first, then the lowest start not begun.
    fn claim(&mut self) -> Option<Job<'s>> {
        if let Some(i) = self.slots.iter().position(|s| matches!(s, Slot::Ready(..))) {
            let Slot::Ready(started, skip) = std::mem::replace(&mut self.slots[i], Slot::Running) else { unreachable!() };
            return Some(Job::Finish(i, Box::new(started), skip));
        }
        let i = self.slots.iter().position(|s| matches!(s, Slot::Waiting))?;
        self.slots[i] = Slot::Running;
        Some(Job::First(i))
    }

    /// Decides every round that can be decided, and ends the rounds where two used starts agree or no start
    /// is left. A round is decided once the rounds before it are finished and its own first phases are done.
    fn advance(&mut self, round: usize) {
        while self.end.is_none() {
            let a = self.decided;
            let Some(runs) =
                self.slots[..a].iter().map(|s| if let Slot::Done(r) = s { Some(r) } else { None }).collect::<Option<Vec<_>>>()
            else {
                return; // polishes of the last round still running
            };
            if a == self.slots.len() || (a > 0 && super::agreed(&runs)) {
                self.finish_rounds(Ok(a));
                return;
            }
            let b = (a + round).min(self.slots.len());
            if self.slots[a..b].iter().any(|s| matches!(s, Slot::Waiting | Slot::Running)) {
                return;
            }
            if let Some(i) = (a..b).find(|&i| matches!(self.slots[i], Slot::Failed(_))) {
                let Slot::Failed(e) = std::mem::replace(&mut self.slots[i], Slot::Running) else { unreachable!() };
                self.finish_rounds(Err(e));
                return;
            }
            self.decide(a, b);
        }
    }

    /// Leaves a stalled start of round `[a, b)` unpolished where it stalled at more than [`HOPELESS`] times
    /// the least effort a converged start reached, in this round or before.
    fn decide(&mut self, a: usize, b: usize) {
        let least = self.slots[..b]
            .iter()
            .filter_map(|s| match s {
                Slot::Done(r) => Some(&r.outcome),
                Slot::Stalled(f) => Some(&f.outcome),
                _ => None,
            })
            .filter(|o| o.converged && o.objective.is_finite())
            .map(|o| o.objective)
            .min_by(f64::total_cmp);
        for i in a..b {
            if !matches!(self.slots[i], Slot::Stalled(_)) {
                continue;
            }
            let Slot::Stalled(f) = std::mem::replace(&mut self.slots[i], Slot::Running) else { unreachable!() };
            let skip = match least {
                Some(l) if i > 0 && f.outcome.objective > HOPELESS * l => Some(format!(
                    "at {:.2}× the least effort a converged start reached ({l:.6e}): left unpolished",
                    f.outcome.objective / l
                )),
                _ => None,
            };
            self.slots[i] = Slot::Ready(f, skip);
        }
        self.decided = b;
    }

    /// Whether a finished start has converged to less effort than the first start's (beyond [`TIE`]), which
    /// the plan then does not keep: its check between the nodes is of no use.
    fn beaten_first(&self) -> bool {
        let converged = |s: &Slot| match s {
            Slot::Done(r) if r.outcome.converged && r.outcome.objective.is_finite() => Some(r.outcome.objective),
            _ => None,
        };
        let Some(first) = converged(&self.slots[0]) else { return false };
        self.slots[1..].iter().filter_map(converged).any(|f| f < first - TIE * first.abs())
    }

    /// Ends the rounds and stops the starts begun ahead of time that they did not use.
    fn finish_rounds(&mut self, end: Result<usize>) {
        let used = *end.as_ref().unwrap_or(&0);
        self.cancels[used..].iter().for_each(Cancel::raise);
        self.end = Some(end);
    }
}

/// What every thread needs: the guesses, the three phases and the shared state.
struct Work<'a, 's, F, P, W> {
    guesses: &'a [Vec<f64>],
    round: usize,
    first: F,
    finish: P,
    stalled: W,
    state: Mutex<State<'s>>,
    changed: Condvar,
}

impl<'s, F, P, W> Work<'_, 's, F, P, W>
where
    F: Fn(&[f64], &Cancel, &mut dyn FnMut(&Progress)) -> Result<Started<'s>> + Sync,
    P: Fn(Started<'s>, bool, &mut dyn FnMut(&Progress)) -> Run + Sync,
    W: Fn(&Started<'s>) -> bool + Sync,
{
    fn lock(&self) -> MutexGuard<'_, State<'s>> {
        self.state.lock().expect("no start panics holding the rounds' state")
    }

    /// A thread's loop: claims jobs until the rounds end. `observer` sees the first start's phases.
    fn serve(&self, observer: &mut dyn FnMut(&Progress)) {
        let mut state = self.lock();
        while state.end.is_none() {
            let Some(job) = state.claim() else {
                state = self.changed.wait(state).expect("no start panics holding the rounds' state");
                continue;
            };
            let (i, cancel) = match &job {
                Job::First(i) | Job::Finish(i, ..) => (*i, state.cancels[*i].clone()),
            };
            drop(state);
            let mut quiet = |_: &Progress| {};
            state = self.complete(i, self.run_caught(job, &cancel, if i == 0 { &mut *observer } else { &mut quiet }));
        }
    }

    /// [`Self::run`], a panic caught (to end the rounds and be raised again on the caller's thread, rather
    /// than leave the others waiting for a start that never finishes).
    fn run_caught(&self, job: Job<'s>, cancel: &Cancel, observer: &mut dyn FnMut(&Progress)) -> std::thread::Result<Slot<'s>> {
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| self.run(job, cancel, observer)))
    }

    /// Stores start `i`'s new state (or the panic that ended the job: the rounds end and every start stops),
    /// decides what can be decided and wakes the waiting threads.
    fn complete(&self, i: usize, slot: std::thread::Result<Slot<'s>>) -> MutexGuard<'_, State<'s>> {
        let mut state = self.lock();
        match slot {
            Ok(slot) => {
                state.slots[i] = slot;
                if state.beaten_first() {
                    state.check_cancel.raise();
                }
                state.advance(self.round);
            }
            Err(panic) => {
                state.panicked.get_or_insert(panic);
                state.check_cancel.raise();
                state.finish_rounds(Ok(0));
            }
        }
        self.changed.notify_all();
        state
    }

    /// One job: a first phase (finished at once where it did not stall, and for the first start), or a
    /// decided polish.
    fn run(&self, job: Job<'s>, cancel: &Cancel, observer: &mut dyn FnMut(&Progress)) -> Slot<'s> {
        match job {
            Job::First(i) => match (self.first)(&self.guesses[i], cancel, &mut *observer) {
                Err(e) => Slot::Failed(e),
                Ok(f) if i == 0 || !(self.stalled)(&f) => Slot::Done((self.finish)(f, true, observer)),
                Ok(f) => Slot::Stalled(f),
            },
            Job::Finish(_, f, skip) => {
                let mut run = (self.finish)(*f, skip.is_none(), observer);
                run.polish_skipped = skip;
                Slot::Done(run)
            }
        }
    }
}

/// Runs the starts from the guesses round by round, `multi.starts` at a time, until the rounds end
/// ([`super::MultiStart::up_to`], [`super::agreed`]) or the guesses do — each start's first phase
/// (`first`, stopped by its flag), then, where it stalled (`stalled`), its polish (`finish`) unless left
/// unpolished ([`HOPELESS`]). The first start runs on this thread with `observer`, and where it converged
/// `check` runs on it at once (module docs); the others on this thread and as many more as rayon's pool has
/// threads. `cancel` stops them all. Returns the used starts and the first start's check, if made.
pub(in crate::plan) fn run_rounds<'s, F, P, W, C, K>(
    guesses: &[Vec<f64>],
    multi: &super::MultiStart,
    cancel: &Cancel,
    observer: &mut dyn FnMut(&Progress),
    (first, finish, stalled): (F, P, W),
    check: C,
) -> Result<(Vec<Run>, Option<K>)>
where
    F: Fn(&[f64], &Cancel, &mut dyn FnMut(&Progress)) -> Result<Started<'s>> + Sync,
    P: Fn(Started<'s>, bool, &mut dyn FnMut(&Progress)) -> Run + Sync,
    W: Fn(&Started<'s>) -> bool + Sync,
    C: FnOnce(Run, &Cancel, &mut dyn FnMut(&Progress)) -> K,
    Started<'s>: Send,
{
    let n = guesses.len();
    let mut slots: Vec<Slot> = (0..n).map(|_| Slot::Waiting).collect();
    slots[0] = Slot::Running; // this thread's, with the observer
    let cancels = (0..n).map(|_| cancel.child()).collect();
    let state = State { slots, decided: 0, end: None, cancels, check_cancel: cancel.child(), panicked: None };
    let work =
        Work { guesses, round: multi.starts.max(1), first, finish, stalled, state: Mutex::new(state), changed: Condvar::new() };
    let helpers = rayon::current_num_threads().saturating_sub(1).min(n - 1);
    let mut checked = None;
    std::thread::scope(|scope| {
        for _ in 0..helpers {
            scope.spawn(|| work.serve(&mut |_| {}));
        }
        let cancel = work.lock().cancels[0].clone();
        drop(work.complete(0, work.run_caught(Job::First(0), &cancel, &mut *observer)));
        let (converged, check_cancel) = {
            let state = work.lock();
            let first = match &state.slots[0] {
                Slot::Done(run) if run.outcome.converged && !state.beaten_first() => Some(run.clone()),
                _ => None,
            };
            (first, state.check_cancel.clone())
        };
        checked = converged.map(|run| check(run, &check_cancel, &mut *observer)).filter(|_| !check_cancel.raised());
        work.serve(&mut |_| {});
    });
    let mut state = work.state.into_inner().expect("no start panics holding the rounds' state");
    if let Some(panic) = state.panicked.take() {
        std::panic::resume_unwind(panic);
    }
    let used = state.end.take().expect("the rounds ended")?;
    let runs =
        state.slots.drain(..used).map(|s| if let Slot::Done(r) = s { r } else { unreachable!("a used start is finished") });
    Ok((runs.collect(), checked))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::run::{finish_start, first_phase};
    use crate::plan::{initial_x, MultiStart, Transcription};

    /// A start that panics ends the rounds: the panic reaches the caller's thread, and no thread waits
    /// forever for the start that never finishes (the double pendulum's automatic starts, the second one
    /// panicking while the first runs on this thread).
    #[test]
    fn a_panicking_start_is_raised_on_the_callers_thread() {
        let task = crate::plan::examples::load("double_pendulum");
        let (spec, settings, solver) = (&task.spec, &task.settings, task.solver);
        let mut problem = Transcription::new(spec).unwrap();
        let x0 = initial_x(spec, &mut problem).unwrap();
        let multi = MultiStart::default();
        let guesses = crate::plan::multistart::guesses(spec, &mut problem, &x0, &multi).unwrap();
        let rounds = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            run_rounds(
                &guesses,
                &multi,
                &Cancel::default(),
                &mut |_| {},
                (
                    |x: &[f64], _: &Cancel, observer: &mut dyn FnMut(&Progress)| {
                        assert!(x == &guesses[0][..], "a start that panics");
                        first_phase(spec, solver, settings, None, x, observer)
                    },
                    |first, polish, observer: &mut dyn FnMut(&Progress)| {
                        finish_start(first, solver, settings, None, polish, observer)
                    },
                    |first: &Started| first.stalled(settings),
                ),
                |_, _, _| (),
            )
        }));
        let panic = rounds.err().expect("the panic reached this thread");
        let message = panic.downcast_ref::<&str>().copied().or(panic.downcast_ref::<String>().map(String::as_str));
        assert_eq!(message, Some("a start that panics"));
    }
}
