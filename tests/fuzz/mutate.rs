//! Mutations of a text file (one input of the mutation fuzzer): line, number, key and byte edits, as
//! proptest values so that a failing case shrinks to the fewest, simplest edits.

use proptest::prelude::*;

/// The numbers a mutation puts in place of a number.
const EDGE_NUMBERS: [&str; 9] = ["1e308", "-1e308", "nan", "inf", "-inf", "0", "-1", "1e-308", "NaN"];

/// One edit; positions are fractions of the text (or of its lines, numbers, keys), as u16 so they shrink.
#[derive(Clone, Debug)]
pub enum Mutation {
    DeleteLine(u16),
    DuplicateLine(u16),
    SwapDigits(u16),
    EdgeNumber(u16, u8),
    Misspell(u16, u8),
    Truncate(u16),
    FlipByte(u16, u8),
}

pub fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        1 => any::<u16>().prop_map(Mutation::DeleteLine),
        1 => any::<u16>().prop_map(Mutation::DuplicateLine),
        1 => any::<u16>().prop_map(Mutation::SwapDigits),
        3 => (any::<u16>(), any::<u8>()).prop_map(|(p, k)| Mutation::EdgeNumber(p, k)),
        2 => (any::<u16>(), any::<u8>()).prop_map(|(p, k)| Mutation::Misspell(p, k)),
        1 => any::<u16>().prop_map(Mutation::Truncate),
        1 => (any::<u16>(), any::<u8>()).prop_map(|(p, b)| Mutation::FlipByte(p, b)),
    ]
}

/// One to three edits.
pub fn mutations() -> impl Strategy<Value = Vec<Mutation>> {
    proptest::collection::vec(mutation(), 1..=3)
}

/// `text` with every edit applied in turn.
pub fn apply(text: &str, edits: &[Mutation]) -> String {
    edits.iter().fold(text.to_string(), |t, m| apply_one(&t, m))
}

/// The `p`-th of `n` (p a u16 fraction), or None when there are none.
fn pick(p: u16, n: usize) -> Option<usize> {
    (n > 0).then(|| p as usize * n / (u16::MAX as usize + 1))
}

fn apply_one(text: &str, m: &Mutation) -> String {
    match *m {
        Mutation::DeleteLine(p) => edit_lines(text, p, |lines, i| {
            lines.remove(i);
        }),
        Mutation::DuplicateLine(p) => edit_lines(text, p, |lines, i| lines.insert(i, lines[i].clone())),
        Mutation::SwapDigits(p) => {
            let pairs: Vec<usize> =
                spans(text, |b| b.is_ascii_digit()).iter().filter(|r| r.len() >= 2).map(|r| r.start).collect();
            let Some(k) = pick(p, pairs.len()) else { return text.to_string() };
            let mut bytes = text.as_bytes().to_vec();
            bytes.swap(pairs[k], pairs[k] + 1);
            String::from_utf8(bytes).unwrap_or_else(|_| text.to_string())
        }
        Mutation::EdgeNumber(p, k) => replace_span(text, &numbers(text), p, EDGE_NUMBERS[k as usize % EDGE_NUMBERS.len()]),
        Mutation::Misspell(p, k) => {
            let words = spans(text, |b| b.is_ascii_alphabetic() || b == b'_');
            let Some(i) = pick(p, words.len()) else { return text.to_string() };
            let word = &text[words[i].clone()];
            let at = k as usize % word.len();
            let mut w = word.as_bytes().to_vec();
            w[at] = if w[at] == b'x' { b'q' } else { b'x' };
            replace_span(text, &words, p, std::str::from_utf8(&w).unwrap_or(word))
        }
        Mutation::Truncate(p) => {
            let at = pick(p, text.len()).unwrap_or(0);
            let at = (0..=at).rev().find(|&i| text.is_char_boundary(i)).unwrap_or(0);
            text[..at].to_string()
        }
        Mutation::FlipByte(p, b) => {
            let Some(at) = pick(p, text.len()).filter(|&i| text.as_bytes()[i].is_ascii()) else { return text.to_string() };
            let mut bytes = text.as_bytes().to_vec();
            bytes[at] = b' ' + b % 95;
            String::from_utf8(bytes).unwrap_or_else(|_| text.to_string())
        }
    }
}

fn edit_lines(text: &str, p: u16, f: impl FnOnce(&mut Vec<String>, usize)) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    if let Some(i) = pick(p, lines.len()) {
        f(&mut lines, i);
    }
    lines.join("\n") + "\n"
}

/// The maximal runs of bytes matching `f`.
fn spans(text: &str, f: impl Fn(u8) -> bool) -> Vec<std::ops::Range<usize>> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if f(b[i]) {
            let start = i;
            while i < b.len() && f(b[i]) {
                i += 1;
            }
            out.push(start..i);
        } else {
            i += 1;
        }
    }
    out
}

/// The numbers of `text`: runs of digits, signs, dots and exponents that hold a digit.
fn numbers(text: &str) -> Vec<std::ops::Range<usize>> {
    let b = text.as_bytes();
    spans(text, |c| c.is_ascii_digit() || matches!(c, b'.' | b'-' | b'+' | b'e' | b'E'))
        .into_iter()
        .filter(|r| b[r.clone()].iter().any(u8::is_ascii_digit))
        .filter(|r| r.start == 0 || !b[r.start - 1].is_ascii_alphabetic())
        .collect()
}

fn replace_span(text: &str, spans: &[std::ops::Range<usize>], p: u16, with: &str) -> String {
    let Some(i) = pick(p, spans.len()) else { return text.to_string() };
    format!("{}{with}{}", &text[..spans[i].start], &text[spans[i].end..])
}
