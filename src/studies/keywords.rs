//! Options given as keywords (the Python package): a JSON object of option names and values,
//! read over the defaults of the options' type, so that the library holds each default once.

use crate::error::{Error, Result};
use serde::de::DeserializeOwned;
use serde::Serialize;

/// The options of `command` named in `keywords` (a JSON object), the others at `T::default()`.
/// An unknown name, a value of the wrong type, or a name outside an option's list is an error
/// naming the keyword.
pub fn from_keywords<T: Serialize + DeserializeOwned + Default>(command: &str, keywords: &str) -> Result<T> {
    let given: serde_json::Map<String, serde_json::Value> = serde_json::from_str(keywords)
        .map_err(|e| Error::invalid("options", keywords, &format!("a JSON object of keywords ({e})")))?;
    let serde_json::Value::Object(defaults) = serde_json::to_value(T::default()).expect("serialisable") else {
        unreachable!("options serialise to an object")
    };
    let mut merged = defaults.clone();
    for (name, value) in given {
        if !defaults.contains_key(&name) {
            let known: Vec<&str> = defaults.keys().map(String::as_str).collect();
            return Err(Error::invalid(
                "keyword",
                &name,
                &format!("a keyword of {command}: {}", known.join(", ")),
            ));
        }
        // Each value alone over the defaults, so that a wrong type names its keyword.
        let mut alone = defaults.clone();
        alone.insert(name.clone(), value.clone());
        if let Err(e) = serde_json::from_value::<T>(serde_json::Value::Object(alone)) {
            if let (Some(text), serde_json::Value::String(_)) = (value.as_str(), &defaults[&name]) {
                // A name that is not one of the option's: serde lists the names it takes.
                let message = e.to_string();
                let names = message.split_once("expected ").map_or(message.as_str(), |(_, n)| n);
                return Err(Error::invalid(&name, text, names));
            }
            return Err(Error::WrongType {
                expected: kind_of(&defaults[&name]).into(),
                name,
                value: value.to_string(),
            });
        }
        merged.insert(name, value);
    }
    Ok(serde_json::from_value(serde_json::Value::Object(merged)).expect("every value checked"))
}

/// The defaults of `T` as keywords (a JSON object).
pub fn default_keywords<T: Serialize + Default>() -> String {
    serde_json::to_string(&T::default()).expect("serialisable")
}

/// What a keyword with this default takes, in words.
fn kind_of(default: &serde_json::Value) -> &'static str {
    match default {
        serde_json::Value::Bool(_) => "true or false",
        serde_json::Value::Number(n) if n.is_u64() => "a whole number",
        serde_json::Value::Number(_) => "a number",
        serde_json::Value::String(_) => "one of its names",
        serde_json::Value::Array(_) => "a list of numbers",
        _ => "a number or None",
    }
}
