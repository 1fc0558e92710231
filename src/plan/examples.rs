//! The paper's experiments as bundled task files (`examples/`), listed by `mintorque examples`.

/// A bundled task file.
pub struct Example {
    /// The file's name without `.toml`, as `mintorque examples` lists it.
    pub name: &'static str,
    /// The file's text.
    pub text: &'static str,
}

impl Example {
    /// The file's first comment line up to its colon: what the experiment is and where the paper has it.
    pub fn summary(&self) -> String {
        let first = self.text.lines().next().unwrap_or("").trim_start_matches('#').trim();
        first.split(':').next().unwrap_or(first).trim().to_string()
    }
}

/// Every bundled example, by name.
pub const ALL: &[Example] = &[
    Example { name: "arm_lift_earth", text: include_str!("../../examples/arm_lift_earth.toml") },
    Example { name: "arm_lift_mars", text: include_str!("../../examples/arm_lift_mars.toml") },
    Example { name: "arm_lift_space", text: include_str!("../../examples/arm_lift_space.toml") },
    Example { name: "arm_lift_space_free", text: include_str!("../../examples/arm_lift_space_free.toml") },
    Example { name: "astronaut_handrail", text: include_str!("../../examples/astronaut_handrail.toml") },
    Example { name: "chin_up_earth", text: include_str!("../../examples/chin_up_earth.toml") },
    Example { name: "chin_up_space", text: include_str!("../../examples/chin_up_space.toml") },
    Example { name: "dip_down_space", text: include_str!("../../examples/dip_down_space.toml") },
    Example { name: "double_pendulum", text: include_str!("../../examples/double_pendulum.toml") },
    Example { name: "fast_lift_strength", text: include_str!("../../examples/fast_lift_strength.toml") },
    Example { name: "leg_lift", text: include_str!("../../examples/leg_lift.toml") },
    Example { name: "leg_lift_mars", text: include_str!("../../examples/leg_lift_mars.toml") },
    Example { name: "leg_lift_space", text: include_str!("../../examples/leg_lift_space.toml") },
    Example { name: "lift_squat", text: include_str!("../../examples/lift_squat.toml") },
    Example { name: "lift_squat_3d", text: include_str!("../../examples/lift_squat_3d.toml") },
    Example { name: "lift_stoop", text: include_str!("../../examples/lift_stoop.toml") },
    Example { name: "lift_stoop_3d", text: include_str!("../../examples/lift_stoop_3d.toml") },
    Example { name: "moon_overhead_reach", text: include_str!("../../examples/moon_overhead_reach.toml") },
    Example { name: "one_hand_carry", text: include_str!("../../examples/one_hand_carry.toml") },
    Example { name: "pendulum", text: include_str!("../../examples/pendulum.toml") },
    Example { name: "push_up", text: include_str!("../../examples/push_up.toml") },
    Example { name: "reach_shelf", text: include_str!("../../examples/reach_shelf.toml") },
    Example { name: "twist_lift", text: include_str!("../../examples/twist_lift.toml") },
    Example { name: "two_arm_reach", text: include_str!("../../examples/two_arm_reach.toml") },
    Example { name: "weight_lift_earth", text: include_str!("../../examples/weight_lift_earth.toml") },
    Example { name: "weight_lift_mars", text: include_str!("../../examples/weight_lift_mars.toml") },
    Example { name: "weight_lift_space", text: include_str!("../../examples/weight_lift_space.toml") },
];

/// The bundled example `name` loaded from `examples/` as `mintorque plan` loads it (for unit tests).
#[cfg(test)]
pub(crate) fn load(name: &str) -> crate::plan::task::Task {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("examples/{name}.toml"));
    crate::plan::task::Task::load(&path).unwrap_or_else(|e| panic!("{e}"))
}
