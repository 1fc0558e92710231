//! OpenSim's ExternalLoads XML (`--loads file.xml`): an `<ExternalLoads>` with `<ExternalForce>` elements
//! and the `<datafile>` (a `.mot`/`.sto` or `.csv`, relative to the XML's folder) holding their columns.
//! Each ExternalForce becomes one [`Load`]: the force (N) of the columns `<force_identifier>x|y|z`, in the
//! axes of `<force_expressed_in_body>`, acting at the point (m) of the columns `<point_identifier>x|y|z` in
//! `<point_expressed_in_body>` (carried along with that body; the origin of `<applied_to_body>` when
//! there is no point identifier), and the moment (N·m) of `<torque_identifier>x|y|z`, in the force's
//! axes, all on `<applied_to_body>`. `ground` is the world. A body is looked up among the model's bodies
//! and frames (a `.osim` body whose frame is not its joint's is a frame of that name). Dropped:
//! `data_source_name` (the `<datafile>` is read), `external_loads_model_kinematics_file` and its filter.

use super::loads::{Load, Loads, Point};
use super::table::{self, Table};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::spatial::Vec3;
use roxmltree::{Document, Node};
use std::path::Path;

/// Reads the ExternalLoads file at `path` and its data file, for `model`.
pub fn read(path: &Path, model: &Model) -> Result<Loads> {
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let doc = Document::parse(&text).map_err(|e| Error::input(&origin, "XML", e.to_string()))?;
    let root = doc
        .descendants()
        .find(|n| n.has_tag_name("ExternalLoads"))
        .ok_or_else(|| Error::input(&origin, "<ExternalLoads>", "the file has no <ExternalLoads> element"))?;
    let datafile = text_of(root, "datafile")
        .ok_or_else(|| Error::input(&origin, "<ExternalLoads>", "has no <datafile> (the forces' .mot/.sto)"))?;
    let data_path = path.parent().unwrap_or(Path::new(".")).join(datafile);
    let data = read_data(&data_path)?;
    let forces: Vec<Node> = root.descendants().filter(|n| n.has_tag_name("ExternalForce")).collect();
    if forces.is_empty() {
        return Err(Error::input(&origin, "<ExternalLoads>", "has no <ExternalForce>"));
    }
    let context = Context { origin: &origin, doc: &doc, data: &data, model };
    let loads = forces.iter().map(|&f| context.load(f)).collect::<Result<_>>()?;
    let time = column(&data, "time").ok_or_else(|| Error::input(&data.origin, "columns", "needs a `time` column (s)"))?;
    let times: Vec<f64> = data.rows.iter().map(|r| r[time]).collect();
    if let Some(k) = times.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Error::input(&data.origin, format!("line {}", data.lines[k + 1]), "the times must increase"));
    }
    if times.is_empty() {
        return Err(Error::input(&data.origin, "rows", "has no rows"));
    }
    Ok(Loads { origin, times, loads })
}

/// The data file: Storage (`inDegrees` not needed) or CSV.
fn read_data(path: &Path) -> Result<Table> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let origin = path.display().to_string();
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("csv") => table::parse_csv(&text, &origin),
        _ => table::parse_storage_of_any_unit(&text, &origin),
    }
}

/// The trimmed text of `node`'s child `tag`, if any and not empty.
fn text_of<'a>(node: Node<'a, '_>, tag: &str) -> Option<&'a str> {
    node.children().find(|c| c.has_tag_name(tag)).and_then(|c| c.text()).map(str::trim).filter(|t| !t.is_empty())
}

fn column(data: &Table, label: &str) -> Option<usize> {
    data.labels.iter().position(|l| l == label)
}

/// What reading one ExternalForce needs.
struct Context<'a> {
    origin: &'a str,
    doc: &'a Document<'a>,
    data: &'a Table,
    model: &'a Model,
}

impl Context<'_> {
    fn error(&self, node: Node, field: &str, message: impl Into<String>) -> Error {
        let name = node.attribute("name").unwrap_or("");
        let line = crate::model::xml::line_of(self.doc, node);
        Error::input(self.origin, format!("line {line}, <ExternalForce name=\"{name}\"> <{field}>"), message)
    }

    /// One ExternalForce as a load.
    fn load(&self, node: Node) -> Result<Load> {
        let applied = text_of(node, "applied_to_body").ok_or_else(|| self.error(node, "applied_to_body", "is missing"))?;
        let frame = self
            .frame(node, "applied_to_body", applied)?
            .ok_or_else(|| self.error(node, "applied_to_body", "is the ground: a load must act on a body of the figure"))?;
        let expressed_in =
            self.frame(node, "force_expressed_in_body", text_of(node, "force_expressed_in_body").unwrap_or("ground"))?;
        let identifier = text_of(node, "force_identifier").ok_or_else(|| self.error(node, "force_identifier", "is missing"))?;
        let force = self.vectors(node, "force_identifier", identifier)?;
        let moment = match text_of(node, "torque_identifier") {
            Some(id) => self.vectors(node, "torque_identifier", id)?,
            None => vec![Vec3::zeros(); force.len()],
        };
        let point = match text_of(node, "point_identifier") {
            Some(id) => {
                let body = text_of(node, "point_expressed_in_body").unwrap_or("ground");
                let expressed_in = self.frame(node, "point_expressed_in_body", body)?;
                Some(Point { values: self.vectors(node, "point_identifier", id)?, expressed_in })
            }
            None => None,
        };
        Ok(Load { frame, force, moment, expressed_in, point })
    }

    /// The model frame of a body name; `None` for `ground`.
    fn frame(&self, node: Node, field: &str, name: &str) -> Result<Option<usize>> {
        if name == "ground" {
            return Ok(None);
        }
        match self.model.frame_index(name) {
            Some(f) => Ok(Some(f)),
            None => Err(self.error(node, field, format!("the model \"{}\" has no body or frame \"{name}\"", self.model.name))),
        }
    }

    /// The columns `IDx`, `IDy`, `IDz` of the data file, row by row.
    fn vectors(&self, node: Node, field: &str, id: &str) -> Result<Vec<Vec3>> {
        let columns: Vec<Option<usize>> = ["x", "y", "z"].iter().map(|a| column(self.data, &format!("{id}{a}"))).collect();
        let [Some(x), Some(y), Some(z)] = columns[..] else {
            let message = format!("\"{id}\": the data file {} needs the columns {id}x, {id}y and {id}z", self.data.origin);
            return Err(self.error(node, field, message));
        };
        Ok(self.data.rows.iter().map(|r| Vec3::new(r[x], r[y], r[z])).collect())
    }
}
