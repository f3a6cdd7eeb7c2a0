//! A small JSON value and writer (the bench adds no dependency for its one output file).

use std::fmt::Write as _;

/// A JSON value. Object keys keep their insertion order.
pub enum Json {
    Null,
    Bool(bool),
    Num(f64),
    Str(String),
    Arr(Vec<Json>),
    Obj(Vec<(String, Json)>),
}

impl Json {
    /// An object from (key, value) pairs.
    pub fn obj<const N: usize>(pairs: [(&str, Json); N]) -> Json {
        Json::Obj(pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
    }

    /// Pretty-printed text (two-space indent); non-finite numbers are written as null.
    pub fn to_pretty(&self) -> String {
        let mut s = String::new();
        self.write(&mut s, 0);
        s.push('\n');
        s
    }

    fn write(&self, s: &mut String, indent: usize) {
        let pad = |s: &mut String, n: usize| s.extend(std::iter::repeat_n(' ', n));
        match self {
            Json::Null => s.push_str("null"),
            Json::Bool(b) => s.push_str(if *b { "true" } else { "false" }),
            Json::Num(x) if !x.is_finite() => s.push_str("null"),
            Json::Num(x) if x.fract() == 0.0 && x.abs() < 1e15 => write!(s, "{}", *x as i64).unwrap(),
            Json::Num(x) => write!(s, "{x}").unwrap(),
            Json::Str(t) => write_str(s, t),
            Json::Arr(v) if v.is_empty() => s.push_str("[]"),
            Json::Arr(v) if v.iter().all(|e| matches!(e, Json::Num(_) | Json::Null | Json::Bool(_))) => {
                s.push('[');
                for (i, e) in v.iter().enumerate() {
                    if i > 0 {
                        s.push_str(", ");
                    }
                    e.write(s, indent);
                }
                s.push(']');
            }
            Json::Arr(v) => {
                s.push_str("[\n");
                for (i, e) in v.iter().enumerate() {
                    pad(s, indent + 2);
                    e.write(s, indent + 2);
                    s.push_str(if i + 1 < v.len() { ",\n" } else { "\n" });
                }
                pad(s, indent);
                s.push(']');
            }
            Json::Obj(m) if m.is_empty() => s.push_str("{}"),
            Json::Obj(m) => {
                s.push_str("{\n");
                for (i, (k, v)) in m.iter().enumerate() {
                    pad(s, indent + 2);
                    write_str(s, k);
                    s.push_str(": ");
                    v.write(s, indent + 2);
                    s.push_str(if i + 1 < m.len() { ",\n" } else { "\n" });
                }
                pad(s, indent);
                s.push('}');
            }
        }
    }
}

fn write_str(s: &mut String, t: &str) {
    s.push('"');
    for c in t.chars() {
        match c {
            '"' => s.push_str("\\\""),
            '\\' => s.push_str("\\\\"),
            '\n' => s.push_str("\\n"),
            '\r' => s.push_str("\\r"),
            '\t' => s.push_str("\\t"),
            c if (c as u32) < 0x20 => write!(s, "\\u{:04x}", c as u32).unwrap(),
            c => s.push(c),
        }
    }
    s.push('"');
}

impl From<f64> for Json {
    fn from(x: f64) -> Json {
        Json::Num(x)
    }
}
impl From<u64> for Json {
    fn from(x: u64) -> Json {
        Json::Num(x as f64)
    }
}
impl From<u32> for Json {
    fn from(x: u32) -> Json {
        Json::Num(x as f64)
    }
}
impl From<usize> for Json {
    fn from(x: usize) -> Json {
        Json::Num(x as f64)
    }
}
impl From<bool> for Json {
    fn from(b: bool) -> Json {
        Json::Bool(b)
    }
}
impl From<&str> for Json {
    fn from(t: &str) -> Json {
        Json::Str(t.to_string())
    }
}
impl From<String> for Json {
    fn from(t: String) -> Json {
        Json::Str(t)
    }
}
impl<T: Into<Json>> From<Option<T>> for Json {
    fn from(o: Option<T>) -> Json {
        o.map_or(Json::Null, Into::into)
    }
}
impl<T: Into<Json>> From<Vec<T>> for Json {
    fn from(v: Vec<T>) -> Json {
        Json::Arr(v.into_iter().map(Into::into).collect())
    }
}
