//! Field-by-field validation of a set file, so that a bad file is reported
//! with the path of the offending field (`vectors[12].a: expected [s,e,m]`)
//! instead of a line and column.

use crate::set::{
    ImageVector, Level, OpVector, PixelVector, SdfVector, Vector, VectorSet, FORMAT_VERSION,
};
use common::image_consts::{HEIGHT, WIDTH};
use common::{Op, F316};
use serde_json::{Map, Value};

/// A validation failure: the field's path and what is wrong with it.
pub(crate) type FieldError = (String, String);

fn err<T>(path: &str, message: impl Into<String>) -> Result<T, FieldError> {
    Err((path.to_string(), message.into()))
}

fn object<'a>(v: &'a Value, path: &str) -> Result<&'a Map<String, Value>, FieldError> {
    v.as_object()
        .map_or_else(|| err(path, "expected an object"), Ok)
}

fn field<'a>(obj: &'a Map<String, Value>, path: &str, name: &str) -> Result<&'a Value, FieldError> {
    obj.get(name)
        .map_or_else(|| err(&format!("{path}.{name}"), "missing field"), Ok)
}

fn string(v: &Value, path: &str) -> Result<String, FieldError> {
    v.as_str()
        .map(str::to_string)
        .map_or_else(|| err(path, "expected a string"), Ok)
}

fn int_in(v: &Value, path: &str, lo: i64, hi: i64) -> Result<i64, FieldError> {
    match v.as_i64() {
        Some(n) if (lo..=hi).contains(&n) => Ok(n),
        _ => err(path, format!("expected an integer in {lo}..={hi}")),
    }
}

fn triple(v: &Value, path: &str) -> Result<F316, FieldError> {
    let words: Option<Vec<i16>> = v.as_array().filter(|a| a.len() == 3).and_then(|a| {
        a.iter()
            .map(|w| w.as_i64().and_then(|n| i16::try_from(n).ok()))
            .collect()
    });
    match words {
        Some(w) => Ok(F316::new(w[0], w[1], w[2])),
        None => err(path, "expected [s,e,m] (three 16-bit integers)"),
    }
}

fn known_fields(obj: &Map<String, Value>, path: &str, allowed: &[&str]) -> Result<(), FieldError> {
    match obj.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => err(
            &format!("{path}.{k}"),
            format!("unknown field (expected {})", allowed.join(", ")),
        ),
        None => Ok(()),
    }
}

fn op_vector(obj: &Map<String, Value>, path: &str, category: String) -> Result<Vector, FieldError> {
    known_fields(obj, path, &["category", "op", "a", "b"])?;
    let op_path = format!("{path}.op");
    let op: Op = string(field(obj, path, "op")?, &op_path)?
        .parse()
        .map_err(|e: common::op::UnknownOp| (op_path.clone(), e.to_string()))?;
    let a = triple(field(obj, path, "a")?, &format!("{path}.a"))?;
    let b = match (op.arity(), obj.get("b")) {
        (2, Some(b)) => Some(triple(b, &format!("{path}.b"))?),
        (2, None) => {
            return err(
                &format!("{path}.b"),
                format!("missing field (`{op}` takes two operands)"),
            )
        }
        (_, Some(_)) => return err(&format!("{path}.b"), format!("`{op}` takes one operand")),
        (_, None) => None,
    };
    Ok(Vector::Op(OpVector { category, op, a, b }))
}

fn sdf_vector(
    obj: &Map<String, Value>,
    path: &str,
    category: String,
) -> Result<Vector, FieldError> {
    known_fields(obj, path, &["category", "p"])?;
    let p_path = format!("{path}.p");
    let items = match field(obj, path, "p")?.as_array() {
        Some(a) if a.len() == 3 => a,
        _ => return err(&p_path, "expected [[s,e,m],[s,e,m],[s,e,m]]"),
    };
    let mut p = [F316::ZERO; 3];
    for (i, item) in items.iter().enumerate() {
        p[i] = triple(item, &format!("{p_path}[{i}]"))?;
    }
    Ok(Vector::Sdf(SdfVector { category, p }))
}

fn pixel_vector(
    obj: &Map<String, Value>,
    path: &str,
    category: String,
) -> Result<Vector, FieldError> {
    known_fields(obj, path, &["category", "x", "y"])?;
    let x = int_in(
        field(obj, path, "x")?,
        &format!("{path}.x"),
        0,
        WIDTH as i64 - 1,
    )? as u16;
    let y = int_in(
        field(obj, path, "y")?,
        &format!("{path}.y"),
        0,
        HEIGHT as i64 - 1,
    )? as u16;
    Ok(Vector::Pixel(PixelVector { category, x, y }))
}

fn vector(v: &Value, path: &str, level: Level) -> Result<Vector, FieldError> {
    let obj = object(v, path)?;
    let category = string(field(obj, path, "category")?, &format!("{path}.category"))?;
    match level {
        Level::Ops => op_vector(obj, path, category),
        Level::Sdf => sdf_vector(obj, path, category),
        Level::Pixels => pixel_vector(obj, path, category),
        Level::Image => {
            known_fields(obj, path, &["category"])?;
            Ok(Vector::Image(ImageVector { category }))
        }
    }
}

/// Build a set from parsed JSON, checking every field.
pub(crate) fn set_from_value(v: &Value) -> Result<VectorSet, FieldError> {
    let obj = object(v, "(top level)")?;
    known_fields(
        obj,
        "(top level)",
        &[
            "format_version",
            "name",
            "level",
            "description",
            "seed",
            "vectors",
        ],
    )
    .map_err(|(p, m)| (p.trim_start_matches("(top level).").to_string(), m))?;
    let top = |name: &str| obj.get(name).map_or_else(|| err(name, "missing field"), Ok);
    let version = int_in(
        top("format_version")?,
        "format_version",
        0,
        i64::from(u32::MAX),
    )? as u32;
    if version != FORMAT_VERSION {
        return err(
            "format_version",
            format!("this harness reads format {FORMAT_VERSION}, the file has {version}"),
        );
    }
    let name = string(top("name")?, "name")?;
    let level: Level = string(top("level")?, "level")?
        .parse()
        .map_err(|m| ("level".to_string(), m))?;
    let description = match obj.get("description") {
        Some(d) => string(d, "description")?,
        None => String::new(),
    };
    let seed = match obj.get("seed") {
        Some(s) => Some(
            s.as_u64()
                .map_or_else(|| err("seed", "expected an unsigned integer"), Ok)?,
        ),
        None => None,
    };
    let items = top("vectors")?
        .as_array()
        .map_or_else(|| err("vectors", "expected an array"), Ok)?;
    let vectors = items
        .iter()
        .enumerate()
        .map(|(i, item)| vector(item, &format!("vectors[{i}]"), level))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(VectorSet {
        format_version: version,
        name,
        level,
        description,
        seed,
        vectors,
    })
}

#[cfg(test)]
mod tests {
    use crate::VectorSet;

    fn error_of(text: &str) -> String {
        VectorSet::parse("t.json", text).unwrap_err().to_string()
    }

    #[test]
    fn errors_name_the_field() {
        let head = r#"{"format_version":1,"name":"t","level":"ops","vectors":["#;
        let good = r#"{"category":"c","op":"add","a":[0,127,8192],"b":[0,0,0]}"#;
        assert_eq!(
            error_of(&format!(
                r#"{head}{good},{{"category":"c","op":"sqrt","a":[0,1]}}]}}"#
            )),
            "t.json: vectors[1].a: expected [s,e,m] (three 16-bit integers)"
        );
        assert_eq!(
            error_of(&format!(
                r#"{head}{{"category":"c","op":"add","a":[0,1,2]}}]}}"#
            )),
            "t.json: vectors[0].b: missing field (`add` takes two operands)"
        );
        assert_eq!(
            error_of(&format!(r#"{head}{{"category":"c","op":"pow","a":[0,1,2]}}]}}"#)),
            "t.json: vectors[0].op: unknown Float316 operation `pow` (expected one of gt, add, sub, mul, div, floor, mod2, sqrt, inv_sqrt, halve, double, quarter)"
        );
        assert_eq!(
            error_of(r#"{"format_version":2,"name":"t","level":"ops","vectors":[]}"#),
            "t.json: format_version: this harness reads format 1, the file has 2"
        );
        assert_eq!(
            error_of(
                r#"{"format_version":1,"name":"t","level":"pixels","vectors":[{"category":"c","x":512,"y":0}]}"#
            ),
            "t.json: vectors[0].x: expected an integer in 0..=511"
        );
        assert_eq!(
            error_of(
                r#"{"format_version":1,"name":"t","level":"sdf","vectors":[{"category":"c","p":[[0,0,0],[0,0,0],[0,0,70000]]}]}"#
            ),
            "t.json: vectors[0].p[2]: expected [s,e,m] (three 16-bit integers)"
        );
        assert!(error_of("{").starts_with("t.json: not valid JSON"));
        assert_eq!(
            error_of(r#"{"format_version":1,"name":"t","level":"ops"}"#),
            "t.json: vectors: missing field"
        );
    }

    #[test]
    fn sets_round_trip_through_text() {
        let text = r#"{"format_version":1,"name":"t","level":"ops","description":"d","seed":7,"vectors":[{"category":"c","op":"add","a":[0,127,8192],"b":[1,0,0]},{"category":"c","op":"sqrt","a":[0,61,0]}]}"#;
        let set = VectorSet::parse("t.json", text).unwrap();
        assert_eq!(VectorSet::parse("again", &set.to_json()).unwrap(), set);
        let one = VectorSet::repro(set.vectors[1].clone());
        assert_eq!(one.to_json().lines().count(), 1);
        assert_eq!(VectorSet::parse("one", &one.to_json()).unwrap(), one);
    }
}
