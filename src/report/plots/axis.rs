//! Axis tick labels.

/// A tick's label on an axis spanning `span`: the decimals a fifth of the span needs (none from 1 up),
/// and a value that rounds to zero written `0`, never `-0.0`.
pub(super) fn tick_label(v: f64, span: f64) -> String {
    let step = (span / 5.0).abs().max(1e-12);
    let decimals = (-step.log10().floor()).clamp(0.0, 12.0) as usize;
    let text = format!("{v:.decimals$}");
    if text.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        return "0".to_string();
    }
    text
}

#[cfg(test)]
mod tests {
    use super::tick_label;

    #[test]
    fn ticks_have_the_spans_decimals_and_no_negative_zero() {
        assert_eq!(tick_label(-1e-17, 0.19), "0");
        assert_eq!(tick_label(-0.05, 0.19), "-0.05");
        assert_eq!(tick_label(20.0, 80.0), "20");
        assert_eq!(tick_label(-0.0, 80.0), "0");
        assert_eq!(tick_label(0.5, 3.0), "0.5");
        assert_eq!(tick_label(150.0, 400.0), "150");
    }
}
