//! A Biovision hierarchy file as written: the joints (`ROOT`/`JOINT` name, `OFFSET`, `CHANNELS`; `End Site`
//! blocks read and dropped), then `MOTION`, `Frames:`, `Frame Time:` and one line of channel values per
//! frame. Nothing is interpreted here (units, axes, the model): [`super::bvh`] maps it onto a model.
//! Refused, naming the file and line: an unknown keyword, a channel name that is not
//! `X|Y|Z` + `position|rotation`, a brace out of place, a value that is not a finite number, a frame line
//! with too many or too few values, a frame count that does not match the lines, a frame time ≤ 0.

use crate::error::{Error, Result};

/// One channel: position or rotation along BVH axis 0 (X), 1 (Y) or 2 (Z).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channel {
    /// `Xposition`, `Yposition`, `Zposition`.
    Position(usize),
    /// `Xrotation`, `Yrotation`, `Zrotation`.
    Rotation(usize),
}

/// One joint of the hierarchy.
#[derive(Clone, Debug)]
pub struct BvhJoint {
    /// Its name.
    pub name: String,
    /// The joint it hangs from (`None` for the ROOT).
    pub parent: Option<usize>,
    /// OFFSET, in the file's unit.
    pub offset: [f64; 3],
    /// Its channels, in the order listed.
    pub channels: Vec<Channel>,
    /// Where its channels start on a frame line.
    pub first_value: usize,
}

/// The file: joints in the order listed (which is the order of the values), frames of values.
#[derive(Clone, Debug)]
pub struct BvhFile {
    /// The file, as named in errors.
    pub origin: String,
    /// Every joint, ROOT first.
    pub joints: Vec<BvhJoint>,
    /// Seconds between frames.
    pub frame_time: f64,
    /// One row of channel values (the file's unit, degrees) per frame.
    pub frames: Vec<Vec<f64>>,
}

/// Words of the text with their line numbers.
struct Words<'a> {
    words: Vec<(usize, &'a str)>,
    next: usize,
    origin: &'a str,
}

impl<'a> Words<'a> {
    fn new(text: &'a str, origin: &'a str) -> Self {
        let words = text.lines().enumerate().flat_map(|(i, l)| l.split_whitespace().map(move |w| (i + 1, w))).collect();
        Words { words, next: 0, origin }
    }

    fn line(&self) -> usize {
        self.words.get(self.next.min(self.words.len().saturating_sub(1))).map_or(0, |w| w.0)
    }

    fn error(&self, message: impl Into<String>) -> Error {
        Error::input(self.origin, format!("line {}", self.line()), message)
    }

    fn take(&mut self, what: &str) -> Result<&'a str> {
        let w = self.words.get(self.next).map(|w| w.1).ok_or_else(|| self.error(format!("ends where {what} was expected")))?;
        self.next += 1;
        Ok(w)
    }

    fn expect(&mut self, word: &str) -> Result<()> {
        let w = self.take(&format!("`{word}`"))?;
        if w.eq_ignore_ascii_case(word) {
            return Ok(());
        }
        self.next -= 1;
        Err(self.error(format!("expected `{word}`, found `{w}`")))
    }

    fn number(&mut self, what: &str) -> Result<f64> {
        let w = self.take(what)?;
        match w.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => {
                self.next -= 1;
                Err(self.error(format!("{what}: \"{w}\" is not a finite number")))
            }
        }
    }
}

/// Parses BVH text; `origin` names the file in errors.
pub fn parse(text: &str, origin: &str) -> Result<BvhFile> {
    let mut words = Words::new(text, origin);
    words.expect("HIERARCHY")?;
    let mut joints = Vec::new();
    words.expect("ROOT")?;
    joint(&mut words, &mut joints, None)?;
    let width: usize = joints.iter().map(|j| j.channels.len()).sum();
    words.expect("MOTION")?;
    words.expect("Frames:")?;
    let count = words.number("the frame count")?;
    words.expect("Frame")?;
    words.expect("Time:")?;
    let frame_time = words.number("the frame time")?;
    if frame_time <= 0.0 {
        return Err(words.error(format!("Frame Time must be above 0 s, got {frame_time}")));
    }
    let frame_time_line = words.words[words.next - 1].0;
    let frames = frame_lines(text, frame_time_line, width, origin)?;
    if count != frames.len() as f64 {
        let message = format!("says Frames: {count} but has {} frame lines", frames.len());
        return Err(Error::input(origin, "MOTION", message));
    }
    Ok(BvhFile { origin: origin.to_string(), joints, frame_time, frames })
}

/// A `ROOT`/`JOINT` block after its keyword: name, `{`, OFFSET, CHANNELS, children, `}`.
fn joint(words: &mut Words, joints: &mut Vec<BvhJoint>, parent: Option<usize>) -> Result<()> {
    let name = words.take("a joint name")?.to_string();
    words.expect("{")?;
    words.expect("OFFSET")?;
    let offset = [words.number("OFFSET x")?, words.number("OFFSET y")?, words.number("OFFSET z")?];
    let first_value = joints.iter().map(|j: &BvhJoint| j.channels.len()).sum();
    let index = joints.len();
    joints.push(BvhJoint { name, parent, offset, channels: Vec::new(), first_value });
    loop {
        let word = words.take("`}`")?;
        match word.to_ascii_uppercase().as_str() {
            "CHANNELS" => joints[index].channels = channels(words)?,
            "JOINT" => joint(words, joints, Some(index))?,
            "END" => end_site(words)?,
            "}" => return Ok(()),
            _ => {
                words.next -= 1;
                return Err(words.error(format!("expected CHANNELS, JOINT, End Site or `}}`, found `{word}`")));
            }
        }
    }
}

/// `CHANNELS n name…`.
fn channels(words: &mut Words) -> Result<Vec<Channel>> {
    let n = words.number("the channel count")?;
    if !(0.0..=6.0).contains(&n) || n.fract() != 0.0 {
        return Err(words.error(format!("CHANNELS {n}: a joint has 0 to 6 channels")));
    }
    (0..n as usize)
        .map(|_| {
            let name = words.take("a channel name")?;
            let axis = "XYZ".find(name.get(..1).unwrap_or("").to_ascii_uppercase().as_str());
            match (axis, name.get(1..).map(str::to_ascii_lowercase).as_deref()) {
                (Some(k), Some("position")) => Ok(Channel::Position(k)),
                (Some(k), Some("rotation")) => Ok(Channel::Rotation(k)),
                _ => {
                    words.next -= 1;
                    Err(words.error(format!("channel \"{name}\" is not Xposition … Zrotation")))
                }
            }
        })
        .collect()
}

/// `End Site { OFFSET x y z }`, read and dropped.
fn end_site(words: &mut Words) -> Result<()> {
    words.expect("Site")?;
    words.expect("{")?;
    words.expect("OFFSET")?;
    for axis in ["x", "y", "z"] {
        words.number(&format!("End Site OFFSET {axis}"))?;
    }
    words.expect("}")
}

/// The frame lines after the line `Frame Time:` is on, `width` values each.
fn frame_lines(text: &str, header_line: usize, width: usize, origin: &str) -> Result<Vec<Vec<f64>>> {
    let mut frames = Vec::new();
    for (i, line) in text.lines().enumerate().skip(header_line) {
        if line.trim().is_empty() {
            continue;
        }
        let field = |k: usize| format!("line {}, value {}", i + 1, k + 1);
        let values: Vec<f64> = line
            .split_whitespace()
            .enumerate()
            .map(|(k, w)| match w.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(Error::input(origin, field(k), format!("\"{w}\" is not a finite number"))),
            })
            .collect::<Result<_>>()?;
        if values.len() != width {
            let message = format!("has {} values; the hierarchy's channels need {width}", values.len());
            return Err(Error::input(origin, format!("line {}", i + 1), message));
        }
        frames.push(values);
    }
    Ok(frames)
}
