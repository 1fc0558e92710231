//! The ergonomic report on the terminal: one table of the joints' torques against their limits, then the
//! low back, the lifting equation and the strength model.

use super::Ergonomics;
use crate::report::summary::limit_text;
use std::fmt::Write as _;

/// A short table for the end of `mintorque plan`: one row per joint, then the totals and the intervals
/// above the limits.
pub fn text_table(e: &Ergonomics) -> String {
    let mut out = String::new();
    let width = e.joints.iter().map(|j| j.name.chars().count()).max().unwrap_or(5).max(5);
    let _ = writeln!(
        out,
        "{:width$}  {:>14}  {:>7}  {:>18}  {:>10}  {:>9}  {:>9}  {:>10}",
        "joint", "peak |τ|", "at (s)", "limit", "% of limit", "above (s)", "work (J)", "peak P (W)"
    );
    for j in &e.joints {
        let unit = j.torque_unit;
        let limit = limit_text(j.strength_limit_negative, j.strength_limit_positive, None, unit);
        let percent = j.peak_fraction_of_limit.map_or_else(|| "-".to_string(), |f| format!("{:.0}%", f * 100.0));
        let peak = format!("{:.2} {unit}", j.peak_abs_torque);
        let _ = writeln!(
            out,
            "{:width$}  {:>14}  {:>7.3}  {:>18}  {:>10}  {:>9.3}  {:>9.2}  {:>10.2}",
            j.name, peak, j.peak_time_s, limit, percent, j.time_above_limit_s, j.absolute_work_j, j.peak_power_w
        );
    }
    let _ = write!(out, "mechanical work: {:.2} J positive, {:.2} J absolute", e.total_positive_work_j, e.total_absolute_work_j);
    if let Some(p) = &e.peak_power {
        let _ = write!(out, "; peak joint power {:.2} W ({} at {:.3} s)", p.value_w, p.joint, p.time_s);
    }
    out.push('\n');
    for j in e.joints.iter().filter(|j| !j.intervals_above_limit.is_empty()) {
        let spans: Vec<String> = j.intervals_above_limit.iter().map(|[a, b]| format!("{a:.3}–{b:.3} s")).collect();
        // How far over, so that a plan within the between-node check's tolerance (0.5 % by default) is not
        // read as one far beyond it.
        let most = j.peak_fraction_of_limit.map_or_else(String::new, |f| format!(" (at most {:.1} % of it)", f * 100.0));
        let _ = writeln!(out, "{} beyond its limit: {}{most}", j.name, spans.join(", "));
    }
    measures_text(e, &mut out);
    out
}

/// The low back, the lifting equation and the strength model, for [`text_table`].
fn measures_text(e: &Ergonomics, out: &mut String) {
    let spans = |v: &[[f64; 2]]| v.iter().map(|[a, b]| format!("{a:.3}–{b:.3} s")).collect::<Vec<_>>().join(", ");
    if let Some(b) = &e.low_back {
        let _ = writeln!(
            out,
            "L5/S1 ({}): peak compression {:.0} N at {:.3} s (NIOSH action limit {:.0} N, maximum {:.0} N); peak shear {:.0} N at {:.3} s",
            b.joint, b.peak_compression_n, b.peak_compression_time_s, b.action_limit_n, b.maximum_permissible_limit_n, b.peak_shear_n, b.peak_shear_time_s
        );
        for (name, v) in
            [("action limit", &b.intervals_above_action_limit), ("maximum permissible limit", &b.intervals_above_maximum_limit)]
        {
            if !v.is_empty() {
                let _ = writeln!(out, "L5/S1 compression above the {name}: {}", spans(v));
            }
        }
    }
    if let Some(l) = &e.lifting_equation {
        let _ = writeln!(
            out,
            "NIOSH lifting equation: load {:.1} kg, {} lifts/min, {} duration, {} coupling, D {:.1} cm: lifting index {:.2}",
            l.load_kg, l.frequency_per_min, l.duration, l.coupling, l.vertical_travel_cm, l.lifting_index
        );
        for (name, end) in [("origin", &l.origin), ("destination", &l.destination)] {
            let (p, m) = (&end.location, &end.multipliers);
            let _ = writeln!(
                out,
                "  {name} ({:.3} s): H {:.1} cm, V {:.1} cm, A {:.1}°; HM {:.3} VM {:.3} DM {:.3} AM {:.3} FM {:.3} CM {:.3}: RWL {:.2} kg, LI {:.2}",
                end.time_s, p.horizontal_cm, p.vertical_cm, p.asymmetry_deg, m.hm, m.vm, m.dm, m.am, m.fm, m.cm, m.rwl_kg, end.lifting_index
            );
        }
    }
    if let Some(s) = &e.strength_model {
        for j in &s.joints {
            let _ = writeln!(
                out,
                "strength {}: {}; peak {:.0}% of it at {:.3} s; {:.1}% of the population capable (least, at {:.3} s)",
                j.name,
                j.source,
                100.0 * j.peak_share,
                j.peak_share_time_s,
                j.least_capable_percent,
                j.least_capable_time_s
            );
        }
        let limiting = s.limiting_joint.as_ref().map_or(String::new(), |j| format!(" ({j} at {:.3} s)", s.limiting_time_s));
        let _ = writeln!(out, "population capable: {:.1}%{limiting}", s.population_capable_percent);
    }
}
