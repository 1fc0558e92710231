//! The sweep table as Parquet (the `parquet` crate's column writer, one row group): numbers as DOUBLE or
//! INT64, text as UTF-8; a parameter column is DOUBLE when every value is a number, else text as written.

use super::row::Row;
use crate::error::{Error, Result};
use parquet::basic::{ConvertedType, Repetition, Type as Physical};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::file::{properties::WriterProperties, writer::SerializedFileWriter};
use parquet::schema::types::Type;
use std::sync::Arc;

/// One column's values.
enum Column {
    Int(Vec<i64>),
    Double(Vec<f64>),
    Text(Vec<ByteArray>),
}

fn text(values: impl Iterator<Item = String>) -> Column {
    Column::Text(values.map(|s| ByteArray::from(s.as_str())).collect())
}

/// The columns of `rows` in `header`'s order (see `table::header`).
fn columns(rows: &[Row], parameters: usize, joints: usize) -> Vec<Column> {
    let mut c = vec![Column::Int(rows.iter().map(|r| r.index as i64).collect())];
    for p in 0..parameters {
        let numbers: Option<Vec<f64>> = rows.iter().map(|r| r.values[p].parse::<f64>().ok()).collect();
        c.push(match numbers {
            Some(n) => Column::Double(n),
            None => text(rows.iter().map(|r| r.values[p].clone())),
        });
    }
    c.push(text(rows.iter().map(|r| r.status.as_str().to_string())));
    c.push(text(rows.iter().map(|r| r.reason.clone())));
    c.push(Column::Double(rows.iter().map(|r| r.effort).collect()));
    c.push(Column::Int(rows.iter().map(|r| r.iterations as i64).collect()));
    c.push(Column::Double(rows.iter().map(|r| r.solve_seconds).collect()));
    c.push(text(rows.iter().map(|r| r.start.to_string())));
    for j in 0..joints {
        c.push(Column::Double(rows.iter().map(|r| r.peak_torque[j]).collect()));
    }
    for j in 0..joints {
        c.push(Column::Double(rows.iter().map(|r| r.peak_share_of_strength[j]).collect()));
    }
    c.push(text(rows.iter().map(|r| r.above_strength.clone())));
    c
}

fn field(name: &str, column: &Column) -> std::result::Result<Arc<Type>, parquet::errors::ParquetError> {
    let (physical, converted) = match column {
        Column::Int(_) => (Physical::INT64, ConvertedType::NONE),
        Column::Double(_) => (Physical::DOUBLE, ConvertedType::NONE),
        Column::Text(_) => (Physical::BYTE_ARRAY, ConvertedType::UTF8),
    };
    Ok(Arc::new(
        Type::primitive_type_builder(name, physical)
            .with_repetition(Repetition::REQUIRED)
            .with_converted_type(converted)
            .build()?,
    ))
}

/// The Parquet file of `rows` under `header`.
pub fn table(header: &[String], rows: &[Row], parameters: usize) -> Result<Vec<u8>> {
    let joints = (header.len() - parameters - 8) / 2;
    let columns = columns(rows, parameters, joints);
    write(header, &columns).map_err(|e| Error::input("sweep.parquet", "table", e.to_string()))
}

fn write(header: &[String], columns: &[Column]) -> std::result::Result<Vec<u8>, parquet::errors::ParquetError> {
    let fields = header.iter().zip(columns).map(|(n, c)| field(n, c)).collect::<std::result::Result<Vec<_>, _>>()?;
    let schema = Arc::new(Type::group_type_builder("sweep").with_fields(fields).build()?);
    let mut bytes = Vec::new();
    let mut writer = SerializedFileWriter::new(&mut bytes, schema, Arc::new(WriterProperties::builder().build()))?;
    let mut group = writer.next_row_group()?;
    let mut next = columns.iter();
    while let Some(mut out) = group.next_column()? {
        match next.next().expect("one column per field") {
            Column::Int(v) => out.typed::<Int64Type>().write_batch(v, None, None)?,
            Column::Double(v) => out.typed::<DoubleType>().write_batch(v, None, None)?,
            Column::Text(v) => out.typed::<ByteArrayType>().write_batch(v, None, None)?,
        };
        out.close()?;
    }
    group.close()?;
    writer.close()?;
    Ok(bytes)
}
