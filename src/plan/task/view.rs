//! The filmstrip's camera (`output.filmstrip_view`): a setting of the task, drawn by
//! `report::filmstrip`. It lives here, below the report, so that the task needs nothing from it.

use crate::spatial::Vec3;

/// Which way the camera looks. The figure faces +x, z is up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// From the figure's right, looking along +y: x to the right, z up (the paper's sagittal figures).
    #[default]
    Side,
    /// From in front, looking along −x: y to the right, z up.
    Front,
    /// From above, looking down −z: x to the right, y up.
    Top,
}

impl View {
    /// Screen coordinates (right, up) and depth (away from the viewer) of a world point.
    pub fn project(self, p: &Vec3) -> ([f64; 2], f64) {
        match self {
            View::Side => ([p.x, p.z], p.y),
            View::Front => ([p.y, p.z], -p.x),
            View::Top => ([p.x, p.y], -p.z),
        }
    }

    /// The view's name in task files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            View::Side => "side",
            View::Front => "front",
            View::Top => "top",
        }
    }
}

impl std::str::FromStr for View {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<View, String> {
        match s.to_ascii_lowercase().as_str() {
            "side" => Ok(View::Side),
            "front" => Ok(View::Front),
            "top" => Ok(View::Top),
            _ => Err(format!("unknown view \"{s}\": use side, front or top")),
        }
    }
}
