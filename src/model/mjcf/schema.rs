//! What the reader knows of MJCF, element by element: the attributes each element may have, and the
//! elements that may appear where. An unknown attribute or element is an error naming the nearest known
//! name (a misspelt `dampng=` would silently drop a damper, `<inertail>` make a body's mass come from its
//! geoms). Elements that carry no dynamics of a kinematic tree (`<visual>`, `<asset>`, `<sensor>`, cameras,
//! lights …) are accepted and not looked into; ones that do but that we cannot model are refused
//! ([`REFUSED_IN_BODY`]) or dropped with a warning ([`DROPPED`]).

/// The children of `<mujoco>` we read.
pub(super) const READ_TOP: &[&str] = &["compiler", "option", "default", "worldbody", "actuator"];
/// The children of `<mujoco>` that carry nothing the tree's dynamics needs.
pub(super) const IGNORED_TOP: &[&str] =
    &["size", "visual", "statistic", "extension", "custom", "asset", "contact", "sensor", "keyframe", "deformable"];
/// Children of `<mujoco>` whose physics is dropped, with the reason given in the warning.
pub(super) const DROPPED: &[(&str, &str)] = &[
    ("equality", "equality constraints are not imported (close loops with the task's constraints)"),
    ("tendon", "tendons are not imported (their springs, dampers and limits are dropped)"),
];
/// Children of `<mujoco>` that are refused.
pub(super) const REFUSED_TOP: &[(&str, &str)] = &[("include", "<include> is not supported: paste the included file in")];

/// Children of `<body>` (and `<worldbody>`).
pub(super) const BODY_CHILDREN: &[&str] = &[
    "inertial",
    "joint",
    "freejoint",
    "geom",
    "site",
    "body",
    "camera",
    "light",
    "plugin",
    "frame",
    "composite",
    "flexcomp",
    "attach",
    "replicate",
];
/// Children of `<body>` that are refused, with the reason.
pub(super) const REFUSED_IN_BODY: &[(&str, &str)] = &[
    ("frame", "<frame> is not supported yet: give its children their own pos/quat"),
    ("composite", "<composite> is not supported"),
    ("flexcomp", "<flexcomp> (deformable bodies) is not supported"),
    ("attach", "<attach> is not supported"),
    ("replicate", "<replicate> is not supported: write the copies out"),
    ("plugin", "engine plugins are not supported"),
];

/// Children of a `<default>` class.
pub(super) const DEFAULT_CHILDREN: &[&str] = &[
    "default",
    "mesh",
    "material",
    "joint",
    "geom",
    "site",
    "camera",
    "light",
    "pair",
    "equality",
    "tendon",
    "general",
    "motor",
    "position",
    "velocity",
    "intvelocity",
    "damper",
    "cylinder",
    "muscle",
    "adhesion",
    "flex",
    "plugin",
];

/// An element's attributes, with [`ORIENTATIONS`].
macro_rules! with_orientation {
    ($($a:literal),*) => { &[$($a,)* "quat", "axisangle", "euler", "xyaxes", "zaxis"] };
}

/// The orientation attributes of a frame (`pos` aside); at most one may be given.
pub(super) const ORIENTATIONS: &[&str] = &["quat", "axisangle", "euler", "xyaxes", "zaxis"];

pub(super) const COMPILER: &[&str] = &[
    "autolimits",
    "boundmass",
    "boundinertia",
    "settotalmass",
    "balanceinertia",
    "strippath",
    "coordinate",
    "angle",
    "fitaabb",
    "eulerseq",
    "meshdir",
    "texturedir",
    "assetdir",
    "discardvisual",
    "usethread",
    "fusestatic",
    "inertiafromgeom",
    "inertiagrouprange",
    "saveinertial",
    "alignfree",
    "exactmeshinertia",
    "convexhull",
];
pub(super) const BODY: &[&str] = with_orientation!("name", "childclass", "pos", "mocap", "gravcomp", "user");
pub(super) const INERTIAL: &[&str] = with_orientation!("pos", "mass", "diaginertia", "fullinertia");
pub(super) const JOINT: &[&str] = &[
    "name",
    "class",
    "type",
    "group",
    "pos",
    "axis",
    "springdamper",
    "limited",
    "actuatorfrclimited",
    "solreflimit",
    "solimplimit",
    "solreffriction",
    "solimpfriction",
    "stiffness",
    "range",
    "actuatorfrcrange",
    "actuatorgravcomp",
    "margin",
    "ref",
    "springref",
    "armature",
    "damping",
    "frictionloss",
    "user",
];
pub(super) const FREEJOINT: &[&str] = &["name", "group", "align"];
pub(super) const GEOM: &[&str] = with_orientation!(
    "name",
    "class",
    "type",
    "contype",
    "conaffinity",
    "condim",
    "group",
    "priority",
    "size",
    "material",
    "friction",
    "mass",
    "density",
    "shellinertia",
    "solmix",
    "solref",
    "solimp",
    "margin",
    "gap",
    "fromto",
    "pos",
    "hfield",
    "mesh",
    "fitscale",
    "rgba",
    "fluidshape",
    "fluidcoef",
    "user"
);
pub(super) const SITE: &[&str] =
    with_orientation!("name", "class", "type", "group", "pos", "material", "size", "fromto", "rgba", "user");
pub(super) const MOTOR: &[&str] = &[
    "name",
    "class",
    "group",
    "ctrllimited",
    "forcelimited",
    "actlimited",
    "ctrlrange",
    "forcerange",
    "actrange",
    "lengthrange",
    "gear",
    "cranklength",
    "joint",
    "jointinparent",
    "tendon",
    "cranksite",
    "slidersite",
    "site",
    "refsite",
    "body",
    "user",
    "nsample",
    "interp",
    "delay",
];

/// MuJoCo's actuator elements: in a `<default>` they all set one shared actuator default.
const ACTUATORS: &[&str] =
    &["general", "motor", "position", "velocity", "intvelocity", "damper", "cylinder", "muscle", "adhesion"];

/// Which default an element kind takes its class values from: its own tag, or `actuator` for every
/// actuator (a `<general ctrlrange>` default applies to `<motor>`s, as in MuJoCo).
pub(super) fn default_key(tag: &str) -> &str {
    if ACTUATORS.contains(&tag) {
        "actuator"
    } else {
        tag
    }
}

/// The known attributes of an element we read (`None`: not one we check).
pub(super) fn attributes_of(tag: &str) -> Option<&'static [&'static str]> {
    Some(match tag {
        "body" => BODY,
        "inertial" => INERTIAL,
        "joint" => JOINT,
        "freejoint" => FREEJOINT,
        "geom" => GEOM,
        "site" => SITE,
        "motor" => MOTOR,
        "compiler" => COMPILER,
        _ => return None,
    })
}
