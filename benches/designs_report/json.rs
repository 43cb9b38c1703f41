//! JSON for the designs benchmark's report and its committed baseline:
//! `serde_json` values (objects keep their keys in insertion order, the
//! `preserve_order` feature), numbers rounded as the report chooses, and
//! values looked up by dotted paths of nested objects.

pub(crate) use serde_json::{json, Value as Json};

/// A count.
pub(crate) fn count(x: usize) -> Json {
    Json::from(x)
}

/// `x` rounded to `digits` decimals (an integer for 0), or `null` if not
/// finite (a quantile of no values is NaN).
pub(crate) fn fixed(x: f64, digits: usize) -> Json {
    if !x.is_finite() {
        Json::Null
    } else if digits == 0 {
        Json::from(x.round() as i64)
    } else {
        number(&format!("{x:.digits$}"))
    }
}

/// `x` rounded to `digits` decimals in exponent form, or `null` if not
/// finite.
pub(crate) fn sci(x: f64, digits: usize) -> Json {
    if x.is_finite() {
        number(&format!("{x:.digits$e}"))
    } else {
        Json::Null
    }
}

/// The number `text` (a rounded value; written back as the shortest text
/// that reads as the same `f64`).
fn number(text: &str) -> Json {
    text.parse::<f64>().map_or(Json::Null, Json::from)
}

/// The value at the dotted `path` of nested objects (`"sweep.converged"`).
pub(crate) fn at<'a>(v: &'a Json, path: &str) -> Option<&'a Json> {
    path.split('.').try_fold(v, |v, key| v.get(key))
}

/// The number at `path` (`None`: missing, `null` or not a number).
pub(crate) fn num(v: &Json, path: &str) -> Option<f64> {
    at(v, path)?.as_f64()
}

/// The string at `path`.
pub(crate) fn text<'a>(v: &'a Json, path: &str) -> Option<&'a str> {
    at(v, path)?.as_str()
}
