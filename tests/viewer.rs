//! The viewer page and the filmstrips: self-contained, complete, and drawable for every kind of figure.
//! The records here are made by hand (a smooth motion between two poses, made-up torques and contact
//! forces), so these tests need no solver; `scripts/browser-test.sh` checks real plans in a browser.

use mintorque::dynamics::{kinematics, Data};
use mintorque::model::human::{HumanParams, Structure};
use mintorque::model::{urdf, Model};
use mintorque::plan_dir::{self, PlanContents, WriteOptions};
use mintorque::report::filmstrip::{filmstrip_png, filmstrip_svg, needs_front_view, View};
use mintorque::report::record::{ContactRecord, PlanRecord, SampleRecord};
use mintorque::report::solids::ObstacleRecord;
use mintorque::report::viewer::{embedded_data, file_url, motion_html, VIEW_FILES};
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn double_pendulum() -> Model {
    urdf::load(&repo().join("models/double_pendulum.urdf")).unwrap()
}

fn human() -> Model {
    Structure::Sagittal.build(HumanParams::default()).unwrap()
}

/// A plan-like record: every joint eases from 0 to `amplitude` (rad) over `duration`, torques follow a sine,
/// and each contact (at the named frames) pushes up with half the figure's weight.
fn record(model: &Model, duration: f64, n: usize, amplitude: f64, contact_frames: &[&str]) -> PlanRecord {
    let nv = model.nv();
    let weight = model.total_mass() * 9.81;
    let mut data = Data::new(model);
    kinematics::placements(model, &mut data, &vec![0.0; nv]);
    let contacts: Vec<ContactRecord> = contact_frames
        .iter()
        .map(|f| {
            let p = kinematics::frame_placement(model, &data, model.frame_index(f).unwrap()).translation;
            ContactRecord {
                name: format!("{f}_contact"),
                frame: f.to_string(),
                target: [p.x, p.y, p.z],
                normal: Some([0.0, 0.0, 1.0]),
            }
        })
        .collect();
    let samples = (0..n)
        .map(|k| {
            let t = duration * k as f64 / (n - 1) as f64;
            let s = 0.5 - 0.5 * (std::f64::consts::PI * t / duration).cos();
            SampleRecord {
                t,
                q: (0..nv).map(|j| amplitude * s * if j % 2 == 0 { 1.0 } else { -0.7 }).collect(),
                qd: vec![0.0; nv],
                qdd: vec![0.0; nv],
                tau: (0..nv).map(|j| 40.0 * (t * 3.0 + j as f64).sin()).collect(),
                contact_forces: contacts.iter().map(|_| [0.1 * weight * s, 0.0, 0.5 * weight]).collect(),
            }
        })
        .collect();
    PlanRecord {
        duration,
        gravity: [0.0, 0.0, -9.81],
        support: (!contacts.is_empty()).then_some([[-0.05, 0.25], [-0.15, 0.15]]),
        contacts,
        ..PlanRecord::of_samples(model, samples)
    }
}

fn human_record() -> (Model, PlanRecord) {
    let model = human();
    let feet = model
        .frames
        .iter()
        .find(|f| f.name.contains("toe"))
        .map(|f| f.name.clone())
        .unwrap_or_else(|| model.frames[0].name.clone());
    let r = record(&model, 1.2, 61, 0.6, &[&feet]);
    (model, r)
}

#[test]
fn page_loads_nothing_from_the_network() {
    let (model, rec) = human_record();
    let html = motion_html(&model, &rec, None);
    let lower = html.to_ascii_lowercase();
    // Nothing to fetch: no external scripts, stylesheets, images or imports.
    for pattern in
        ["<script src", " src=\"http", " src='http", "href=\"http", "href='http", "url(http", "@import", "import(\"http"]
    {
        assert!(!lower.contains(pattern), "the page references {pattern}");
    }
    // The only absolute URLs are XML namespace names (never fetched), from three.js itself.
    for (i, _) in lower.match_indices("http") {
        let rest = &lower[i..];
        if rest.starts_with("http://") || rest.starts_with("https://") {
            assert!(rest.starts_with("http://www.w3.org/"), "unexpected URL at byte {i}: {}", &rest[..rest.len().min(60)]);
        }
    }
    assert!(html.contains("window.mintorque"), "the test hook is missing");
    assert!(html.contains("id=\"scrubber\""));
    assert!(
        html.contains("Copyright © 2010-2026 three.js authors") || html.contains("three.js authors"),
        "three.js licence not inlined"
    );
}

#[test]
fn embedded_data_has_a_placement_per_body_per_sample() {
    let (model, rec) = human_record();
    let data = embedded_data(&motion_html(&model, &rec, None)).expect("the page embeds parseable JSON");
    let placements = data["placements"].as_array().unwrap();
    assert_eq!(placements.len(), rec.samples.len());
    for row in placements {
        let row = row.as_array().unwrap();
        assert_eq!(row.len(), model.bodies.len());
        for pose in row {
            let p: Vec<f64> = pose.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
            assert_eq!(p.len(), 7);
            let qn = (p[3] * p[3] + p[4] * p[4] + p[5] * p[5] + p[6] * p[6]).sqrt();
            assert!((qn - 1.0).abs() < 1e-5, "quaternion norm {qn}");
        }
    }
    // The positions are the kinematics' own, not something the page works out.
    let k = rec.samples.len() / 2;
    let mut d = Data::new(&model);
    kinematics::placements(&model, &mut d, &rec.samples[k].q);
    for (b, om) in d.oMi[..model.bodies.len()].iter().enumerate() {
        let got: Vec<f64> = placements[k][b].as_array().unwrap()[..3].iter().map(|x| x.as_f64().unwrap()).collect();
        let want = om.translation;
        assert!(got.iter().zip(want.iter()).all(|(g, w)| (g - w).abs() < 1e-5), "body {b}: {got:?} vs {want:?}");
    }
    assert_eq!(data["bodies"].as_array().unwrap().len(), model.bodies.len());
    assert_eq!(data["times"].as_array().unwrap().len(), rec.samples.len());
    assert_eq!(data["contacts"].as_array().unwrap().len(), 1);
    assert!(data["support"].is_array());
    let shapes: usize = data["bodies"].as_array().unwrap().iter().map(|b| b["shapes"].as_array().unwrap().len()).sum();
    assert_eq!(shapes, model.bodies.iter().map(|b| b.shapes.len()).sum::<usize>());
}

#[test]
fn summary_is_embedded_and_bad_text_is_ignored() {
    let model = double_pendulum();
    let rec = record(&model, 1.0, 11, 1.0, &[]);
    let data = embedded_data(&motion_html(&model, &rec, Some(r#"{"objective": 12.5, "joints": []}"#))).unwrap();
    assert_eq!(data["summary"]["objective"], 12.5);
    let data = embedded_data(&motion_html(&model, &rec, Some("not json"))).unwrap();
    assert!(data["summary"].is_null());
}

#[test]
fn names_cannot_break_out_of_the_page() {
    let mut model = double_pendulum();
    model.name = "evil</script><script>alert(1)</script>".into();
    let mut rec = record(&model, 1.0, 5, 1.0, &[]);
    rec.model_name = model.name.clone();
    let html = motion_html(&model, &rec, None);
    assert!(!html.contains("<script>alert"), "a name closed the script element");
    assert_eq!(embedded_data(&html).unwrap()["model"], model.name.as_str());
}

#[test]
fn shapeless_figure_is_drawn_with_sticks() {
    let model = double_pendulum();
    assert!(model.bodies.iter().all(|b| b.shapes.is_empty()), "the double pendulum should have no shapes");
    let rec = record(&model, 1.5, 31, 2.0, &[]);
    let data = embedded_data(&motion_html(&model, &rec, None)).unwrap();
    let sticks: Vec<usize> = data["bodies"].as_array().unwrap().iter().map(|b| b["sticks"].as_array().unwrap().len()).collect();
    // The upper link points at the elbow; the lower one, a leaf, at twice its centre of mass.
    assert!(sticks[1] >= 1 && sticks[2] >= 1, "sticks per body: {sticks:?}");
    let svg = filmstrip_svg(&model, &rec, 6, View::Side);
    assert!(svg.matches("class=\"stick\"").count() >= 2 * 6, "too few sticks in the filmstrip");
}

#[test]
fn filmstrip_has_the_requested_frames_in_every_view() {
    let (model, rec) = human_record();
    for view in [View::Side, View::Front, View::Top] {
        for frames in [1, 2, 7] {
            let svg = filmstrip_svg(&model, &rec, frames, view);
            assert_eq!(svg.matches("<g class=\"frame\"").count(), frames, "{view:?} {frames}");
            assert_eq!(svg.matches("class=\"time\"").count(), frames);
            assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
            assert!(!svg.contains("NaN") && !svg.contains("inf"), "non-finite coordinates in {view:?}");
        }
    }
    // Evenly spaced from start to end.
    let svg = filmstrip_svg(&model, &rec, 4, View::Side);
    for label in ["t = 0.00 s", "t = 0.40 s", "t = 0.80 s", "t = 1.20 s"] {
        assert!(svg.contains(label), "missing {label}");
    }
    assert!(svg.contains("class=\"force\""), "the contact force is not drawn");
}

#[test]
fn filmstrip_png_is_a_png() {
    let model = double_pendulum();
    let rec = record(&model, 1.0, 11, 1.0, &[]);
    let png = filmstrip_png(&model, &rec, 5, View::Side).unwrap();
    assert!(png.starts_with(&[0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n']));
    assert!(png.len() > 1000);
}

/// The value of attribute `name` in element text `e`.
fn attr(e: &str, name: &str) -> Option<f64> {
    let at = e.find(&format!(" {name}=\""))? + name.len() + 3;
    e[at..at + e[at..].find('"')?].parse().ok()
}

/// A frame's panel `[x, y, width, height]` and the points drawn in it.
type PanelPoints = ([f64; 4], Vec<(f64, f64)>);

/// Every drawn point of the figure in each frame of a filmstrip (sticks' and forces' ends, joint dots with
/// their radius, outline corners), with the frame's panel `[x, y, width, height]`.
fn frame_points(svg: &str) -> Vec<PanelPoints> {
    svg.split("<g class=\"frame\"")
        .skip(1)
        .map(|frame| {
            let panel = frame.split("<rect class=\"panel\"").nth(1).expect("a panel rectangle");
            let rect = ["x", "y", "width", "height"].map(|n| attr(panel, n).unwrap());
            let mut points = vec![];
            for e in frame.split('<').filter(|e| e.contains("class=\"stick\"") || e.contains("class=\"force\"")) {
                let [x1, y1, x2, y2] = ["x1", "y1", "x2", "y2"].map(|n| attr(e, n).unwrap());
                points.extend([(x1, y1), (x2, y2)]);
            }
            for e in frame.split('<').filter(|e| e.starts_with("circle class=\"joint\"")) {
                let ([x, y], r) = (["cx", "cy"].map(|n| attr(e, n).unwrap()), attr(e, "r").unwrap());
                points.extend([(x - r, y - r), (x + r, y + r)]);
            }
            for e in frame.split("<polygon points=\"").skip(1) {
                let list = &e[..e.find('"').unwrap()];
                points.extend(list.split_whitespace().map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    (x.parse::<f64>().unwrap(), y.parse::<f64>().unwrap())
                }));
            }
            (rect, points)
        })
        .collect()
}

#[test]
fn every_part_of_the_figure_stays_inside_its_panel_with_a_margin() {
    let pendulum = urdf::load(&repo().join("models/pendulum.urdf")).unwrap();
    let cases = [
        (pendulum.clone(), record(&pendulum, 1.0, 41, 2.5, &[])),
        (double_pendulum(), record(&double_pendulum(), 1.0, 41, 2.0, &[])),
        human_record(),
    ];
    for (model, rec) in &cases {
        for view in [View::Side, View::Front, View::Top] {
            let svg = filmstrip_svg(model, rec, 8, view);
            let mut nearest = f64::INFINITY;
            for (k, ([x, y, w, h], points)) in frame_points(&svg).into_iter().enumerate() {
                assert!(!points.is_empty(), "{} {view:?} frame {k}: nothing drawn", model.name);
                for (px, py) in points {
                    let margin = (px - x).min(x + w - px).min(py - y).min(y + h - py);
                    assert!(
                        margin >= 8.0,
                        "{} {view:?} frame {k}: ({px}, {py}) is {margin:.1} px from its panel's edge",
                        model.name
                    );
                    nearest = nearest.min(margin);
                }
            }
            // The figure fills its panels: something comes within the margin's reach of an edge.
            assert!(nearest < 20.0, "{} {view:?}: the figure keeps {nearest:.1} px from every edge", model.name);
            // The legend names the joint dots' colours, below every panel.
            let legend_y = attr(svg.split("<g class=\"legend\"").nth(1).unwrap(), "y").unwrap();
            assert!(svg.contains("|τ| / strength") && svg.contains("url(#joint-load)"));
            assert!(frame_points(&svg).iter().all(|([_, y, _, h], _)| y + h < legend_y));
        }
    }
}

#[test]
fn a_front_filmstrip_goes_beside_the_side_one_for_a_3d_plan_only() {
    let whole = Structure::WholeBody.build(HumanParams::default()).unwrap();
    let planar = [double_pendulum(), urdf::load(&repo().join("models/pendulum.urdf")).unwrap(), human()];
    let whole_rec = record(&whole, 1.0, 11, 0.3, &[]);
    assert!(needs_front_view(&whole, &whole_rec), "the whole body spreads sideways");
    for model in &planar {
        assert!(!needs_front_view(model, &record(model, 1.0, 11, 1.0, &[])), "{} is planar", model.name);
    }
    for (model, rec, front) in
        [(whole.clone(), whole_rec, true), (planar[0].clone(), record(&planar[0], 1.0, 11, 1.0, &[]), false)]
    {
        let dir = scratch(&format!("front-{}", model.name));
        write_plan_dir(&dir, &model, &rec);
        let loaded = plan_dir::load(&dir).unwrap();
        for name in ["filmstrip-front.svg", "filmstrip-front.png"] {
            assert_eq!(loaded.manifest.files.contains_key(name), front, "{}: {name}", model.name);
            assert_eq!(dir.join(name).exists(), front, "{}: {name}", model.name);
        }
        assert!(loaded.manifest.files.contains_key("filmstrip.svg"));
        if front {
            assert!(std::fs::read_to_string(dir.join("filmstrip-front.svg")).unwrap().contains("front view"));
        }
    }
}

/// A figure held by the world stands on a ground line (and the viewer draws its floor); the same figure
/// floating free has neither.
#[test]
fn a_free_floating_figure_is_drawn_without_ground() {
    const GROUND: &str = r##"stroke="#9aa5b1" stroke-width="1.5""##;
    let held = Structure::WholeBody.build(HumanParams::default()).unwrap();
    let free = mintorque::model::human::build_free(Structure::WholeBody, HumanParams::default()).unwrap();
    for (model, ground) in [(held, true), (free, false)] {
        let rec = record(&model, 1.0, 11, 0.3, &[]);
        for view in [View::Side, View::Front] {
            let svg = filmstrip_svg(&model, &rec, 4, view);
            assert_eq!(svg.contains(GROUND), ground, "{} ({view:?})", model.name);
        }
        let data = embedded_data(&motion_html(&model, &rec, None)).expect("the page embeds parseable JSON");
        assert_eq!(data["floor"].as_bool(), Some(ground), "{}: the viewer's floor", model.name);
    }
}

/// Writes a plan directory of a hand-made record through `plan_dir`, as `mintorque plan` would.
fn write_plan_dir(dir: &Path, model: &Model, rec: &PlanRecord) {
    plan_dir::write(dir, &PlanContents::from_record(model.clone(), rec.clone()), &WriteOptions::default()).unwrap();
}

/// (Re)generates the views of a plan directory, as `mintorque view DIR` does.
fn write_view_files(dir: &Path) -> plan_dir::Result<PathBuf> {
    plan_dir::write_views(dir, None)
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mintorque-viewer-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn view_files_are_written_into_the_plan_directory() {
    let (model, rec) = human_record();
    let dir = scratch("view-files");
    write_plan_dir(&dir, &model, &rec);
    write_view_files(&dir).unwrap();
    for name in VIEW_FILES {
        assert!(dir.join(name).metadata().unwrap().len() > 0, "{name} is empty");
    }
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .filter(|n| n.to_string_lossy().starts_with('.'))
        .collect();
    assert!(leftovers.is_empty(), "hidden files inside the plan: {leftovers:?}");
    let beside: Vec<_> = std::fs::read_dir(dir.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("view-files") && (n.contains("staging") || n.contains(".old")))
        .collect();
    assert!(beside.is_empty(), "staging directories left behind: {beside:?}");
    // Again, over the old files; another view goes beside the plan's own filmstrip, not over it.
    write_view_files(&dir).unwrap();
    let side = std::fs::read(dir.join("filmstrip.svg")).unwrap();
    plan_dir::write_views(&dir, Some(View::Front)).unwrap();
    assert_eq!(std::fs::read(dir.join("filmstrip.svg")).unwrap(), side, "the plan's filmstrip is kept");
    let front = std::fs::read_to_string(dir.join("filmstrip-front.svg")).unwrap();
    assert_ne!(front.as_bytes(), &side[..]);
    assert!(dir.join("filmstrip-front.png").exists());
    // Both belong to the plan: it loads, every file checked.
    let loaded = plan_dir::load(&dir).unwrap();
    assert!(loaded.manifest.files.contains_key("filmstrip-front.svg"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_record_that_does_not_fit_its_model_is_an_error_not_a_panic() {
    let model = double_pendulum();
    let mut rec = record(&model, 1.0, 5, 1.0, &[]);
    rec.samples[3].q.pop();
    let dir = scratch("bad-record");
    let err = plan_dir::write(&dir, &PlanContents::from_record(model.clone(), rec.clone()), &WriteOptions::default())
        .unwrap_err()
        .to_string();
    assert!(err.contains("samples[3]"), "{err}");
    assert!(!dir.exists(), "nothing is written for a record that does not fit its model");
    // Drawing it anyway (as a library caller might) still does not panic.
    let _ = motion_html(&model, &rec, None);
    let _ = filmstrip_svg(&model, &rec, 3, View::Side);
}

/// Pages for `scripts/browser-test.sh` to open, from these hand-made records: a shapeless double pendulum
/// and the sagittal human with a contact and a support rectangle.
#[test]
fn writes_pages_for_the_browser_test() {
    let out = repo().join("target/browser-artifacts");
    let (model, rec) = human_record();
    let dp = double_pendulum();
    let dp_rec = record(&dp, 1.5, 76, 2.0, &[]);
    // A revolute and a prismatic joint: the chart offers torque (N·m) and force (N) on separate axes.
    let mut mixed = double_pendulum();
    mixed.joints[2].kind = mintorque::model::JointKind::Prismatic;
    let mixed_rec = record(&mixed, 1.5, 76, 0.3, &[]);
    for (name, model, rec) in [("human", &model, &rec), ("double-pendulum", &dp, &dp_rec), ("mixed", &mixed, &mixed_rec)] {
        let dir = out.join(format!("synthetic-{name}"));
        write_plan_dir(&dir, model, rec);
        write_view_files(&dir).unwrap();
    }
}

#[test]
fn views_parse_and_paths_become_file_urls() {
    assert_eq!("Side".parse::<View>(), Ok(View::Side));
    assert_eq!("top".parse::<View>(), Ok(View::Top));
    assert!("oblique".parse::<View>().unwrap_err().contains("side, front or top"));
    assert_eq!(file_url(Path::new("/tmp/a plan/motion.html")), "file:///tmp/a%20plan/motion.html");
}

// ---- Keep-out zones ----

/// A box obstacle 0.6 m across in front of the human's hips, as `plan.json` records it.
fn box_record(name: &str, x: f64, zone: bool) -> ObstacleRecord {
    ObstacleRecord {
        name: name.into(),
        kind: "box".into(),
        point: [x, 0.0, 0.5],
        axis: [0.0; 3],
        radius: None,
        length: None,
        half_size: Some([0.1, 0.3, 0.3]),
        axes: Some([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
        zone,
    }
}

/// The `<polygon …/>` elements of `svg` whose attributes contain every one of `parts`.
fn polygons_with(svg: &str, parts: &[&str]) -> usize {
    svg.lines().filter(|l| l.trim_start().starts_with("<polygon") && parts.iter().all(|p| l.contains(p))).count()
}

#[test]
fn a_keep_out_zone_is_drawn_dashed_without_fill_and_a_solid_filled() {
    let (model, mut rec) = human_record();
    let frames = 3;
    rec.obstacles = vec![box_record("crate", 0.4, false), box_record("behind", -0.3, true)];
    let svg = filmstrip_svg(&model, &rec, frames, View::Side);
    let solid = [r##"fill="#b08d5b""##];
    let zone = [r#"class="zone""#, r#"fill="none""#, "stroke-dasharray"];
    assert_eq!(polygons_with(&svg, &solid), frames, "the crate, filled, once a frame");
    assert_eq!(polygons_with(&svg, &zone), frames, "the zone, dashed and unfilled, once a frame");
    assert!(svg.contains(">obstacle<") && svg.contains(">keep-out zone<"), "both in the legend");

    // The opposite: both solid, so two filled boxes a frame and no zone anywhere.
    rec.obstacles[1].zone = false;
    let svg = filmstrip_svg(&model, &rec, frames, View::Side);
    assert_eq!(polygons_with(&svg, &solid), 2 * frames);
    assert_eq!(polygons_with(&svg, &[r#"class="zone""#]), 0);
    assert!(!svg.contains("keep-out zone"));

    // A strip narrower than the legend wraps it into rows: every label starts inside the picture, and
    // the picture is taller by the rows added.
    rec.obstacles[1].zone = true;
    let narrow = filmstrip_svg(&model, &rec, 6, View::Front);
    let width = attr(&narrow, "width").unwrap();
    let legend = narrow.split("<g class=\"legend\"").nth(1).unwrap();
    let labels: Vec<(f64, f64)> =
        legend.lines().filter(|l| l.starts_with("<text")).map(|l| (attr(l, "x").unwrap(), attr(l, "y").unwrap())).collect();
    assert!(legend.contains(">keep-out zone<") && labels.iter().all(|(x, _)| *x < width - 40.0), "{labels:?} in {width}");
    let rows = labels.iter().map(|(_, y)| y.round() as i64).collect::<std::collections::BTreeSet<_>>().len();
    assert!(rows > 1, "one legend row in a strip {width} px wide");
    assert!(attr(&narrow, "height").unwrap() > labels.iter().map(|l| l.1).fold(0.0, f64::max));
}

#[test]
fn the_viewer_gets_the_zone_flag_and_old_records_load_as_solids() {
    let (model, mut rec) = human_record();
    rec.obstacles = vec![box_record("crate", 0.4, false), box_record("behind", -0.3, true)];
    let html = motion_html(&model, &rec, None);
    let data = embedded_data(&html).unwrap();
    let zones: Vec<bool> = data["obstacles"].as_array().unwrap().iter().map(|o| o["zone"].as_bool().unwrap()).collect();
    assert_eq!(zones, [false, true]);
    assert!(html.contains("o.zone ? zoneMesh(o.shape)"), "the page draws a zone by its edges");
    // A plan.json written before the field: the obstacle is a solid.
    let mut old = serde_json::to_value(box_record("crate", 0.4, true)).unwrap();
    old.as_object_mut().unwrap().remove("zone");
    assert!(!serde_json::from_value::<ObstacleRecord>(old).unwrap().zone);
}
