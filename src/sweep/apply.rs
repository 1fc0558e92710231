//! Setting a task field by its dotted path: `environment.payload[0].mass = 5.0` in the task file's TOML
//! before it is parsed, so that every value goes through the task file's own checks.

/// One step of a dotted path: a key, then optionally an index into the array it names.
fn steps(path: &str) -> Result<Vec<(String, Option<usize>)>, String> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (key, index) = match part.split_once('[') {
            None => (part, None),
            Some((key, rest)) => {
                let i = rest.strip_suffix(']').and_then(|s| s.parse::<usize>().ok());
                let Some(i) = i else { return Err(format!("\"{part}\": an index is written key[0]")) };
                (key, Some(i))
            }
        };
        if key.is_empty() {
            return Err(format!("\"{path}\" has an empty key"));
        }
        out.push((key.to_string(), index));
    }
    Ok(out)
}

/// Sets `path` in `doc` to `value`, creating missing tables on the way (the task file's schema then says
/// whether the field exists). An index must name an existing array entry.
pub fn set(doc: &mut toml::Table, path: &str, value: toml::Value) -> Result<(), String> {
    let steps = steps(path)?;
    let mut table = doc;
    for (n, (key, index)) in steps.iter().enumerate() {
        let last = n + 1 == steps.len();
        if last && index.is_none() {
            table.insert(key.clone(), value);
            return Ok(());
        }
        if index.is_some() && !table.contains_key(key) {
            return Err(format!("\"{key}\" has 0 entries, there is no [{}]", index.unwrap_or(0)));
        }
        let entry = table.entry(key.clone()).or_insert_with(|| toml::Value::Table(toml::Table::new()));
        let slot = match index {
            None => entry,
            Some(i) => {
                let toml::Value::Array(items) = entry else { return Err(format!("\"{key}\" is not an array")) };
                let len = items.len();
                items.get_mut(*i).ok_or_else(|| format!("\"{key}\" has {len} entries, there is no [{i}]"))?
            }
        };
        if last {
            *slot = value;
            return Ok(());
        }
        let toml::Value::Table(next) = slot else { return Err(format!("\"{key}\" is not a table")) };
        table = next;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::set;

    #[test]
    fn sets_nested_fields_indices_and_new_tables() {
        let mut doc: toml::Table = toml::from_str("[model]\nstature = 1.8\n[[environment.payload]]\nmass = 1.0\n").unwrap();
        set(&mut doc, "model.stature", 1.6.into()).unwrap();
        set(&mut doc, "environment.payload[0].mass", 5.0.into()).unwrap();
        set(&mut doc, "objective.weights.elbow", 2.0.into()).unwrap();
        assert_eq!(doc["model"]["stature"].as_float(), Some(1.6));
        assert_eq!(doc["environment"]["payload"][0]["mass"].as_float(), Some(5.0));
        assert_eq!(doc["objective"]["weights"]["elbow"].as_float(), Some(2.0));
        assert!(set(&mut doc, "environment.payload[3].mass", 1.0.into()).unwrap_err().contains("has 1 entries"));
        assert!(set(&mut doc, "model.stature.x", 1.0.into()).unwrap_err().contains("not a table"));
        assert!(set(&mut doc, "model[x", 1.0.into()).is_err());
    }
}
