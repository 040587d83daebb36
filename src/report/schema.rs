//! The JSON Schema of every contract, derived from the serde types
//! (schemars, a dev-dependency: this module is the library's unit test),
//! published in `docs/guide/schema/NAME.json` and shown in
//! `docs/guide/json.md`. The test fails when either is stale;
//! `STICKY_BLESS=1 cargo test --release --lib report::schema` rewrites them.
//! `tests/json_schema.rs` validates real outputs against the published
//! files.

use std::path::{Path, PathBuf};

use schemars::{schema_for, Schema};

use crate::claims::coq::CoqRow;
use crate::claims::json::ClaimJson;
use crate::prove::json::ProofRecord;
use crate::report::compare::json::ReportJson;
use crate::report::export::ExportJson;
use crate::report::json::{ContinuumJson, EventsJson, StateJson};

/// Every contract: its file stem and its schema.
fn contracts() -> Vec<(&'static str, Schema)> {
    vec![
        ("state", schema_for!(StateJson)),
        ("events", schema_for!(EventsJson)),
        ("continuum", schema_for!(ContinuumJson)),
        ("compare", schema_for!(ReportJson)),
        ("export", schema_for!(ExportJson)),
        ("prove", schema_for!(ProofRecord)),
        ("coq", schema_for!(Vec<CoqRow>)),
        ("claims", schema_for!(Vec<ClaimJson>)),
    ]
}

fn docs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide")
}

/// Every object of the contracts has all its keys, always (`null` where a
/// value is absent), and no other: each `properties` becomes `required`
/// and closed.
fn closed(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Object(map) => {
            if let Some(serde_json::Value::Object(props)) = map.get("properties") {
                let keys = props
                    .keys()
                    .cloned()
                    .map(serde_json::Value::String)
                    .collect();
                map.insert("required".into(), serde_json::Value::Array(keys));
                map.insert("additionalProperties".into(), false.into());
            }
            map.values_mut().for_each(closed);
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(closed),
        _ => {}
    }
}

/// The schema as published: closed, pretty JSON and a final newline.
fn text(schema: &Schema) -> String {
    let mut v = serde_json::to_value(schema).expect("a schema serialises");
    closed(&mut v);
    let mut s = serde_json::to_string_pretty(&v).expect("a schema serialises");
    s.push('\n');
    s
}

/// The guide's block for `name`: between `<!-- schema NAME -->` and
/// `<!-- /schema -->`.
fn block(name: &str, schema: &str) -> String {
    format!(
        "<!-- schema {name} -->\n<details><summary>JSON Schema: <a href=\"schema/{name}.json\">schema/{name}.json</a></summary>\n\n```json\n{schema}```\n\n</details>\n<!-- /schema -->"
    )
}

/// Replaces the block of `name` in `guide`; `None` when it has none.
fn replace_block(guide: &str, name: &str, new: &str) -> Option<String> {
    let open = format!("<!-- schema {name} -->");
    let start = guide.find(&open)?;
    let end = start + guide[start..].find("<!-- /schema -->")? + "<!-- /schema -->".len();
    Some([&guide[..start], new, &guide[end..]].concat())
}

#[test]
fn published_schemas_are_current() {
    let bless = std::env::var_os("STICKY_BLESS").is_some();
    let guide_path = docs().join("json.md");
    let mut guide = std::fs::read_to_string(&guide_path).expect("docs/guide/json.md");
    let mut stale = Vec::new();
    for (name, schema) in contracts() {
        let schema = text(&schema);
        let file = docs().join(format!("schema/{name}.json"));
        if std::fs::read_to_string(&file).ok().as_deref() != Some(schema.as_str()) {
            stale.push(format!("docs/guide/schema/{name}.json"));
            if bless {
                std::fs::create_dir_all(file.parent().expect("a folder")).expect("mkdir");
                std::fs::write(&file, &schema).expect("write the schema");
            }
        }
        let new = block(name, &schema);
        match replace_block(&guide, name, &new) {
            Some(g) if g == guide => {}
            Some(g) => {
                stale.push(format!("json.md's block `{name}`"));
                guide = g;
            }
            None => stale.push(format!("json.md has no `<!-- schema {name} -->` block")),
        }
    }
    if bless {
        std::fs::write(&guide_path, &guide).expect("write json.md");
    }
    assert!(
        bless || stale.is_empty(),
        "stale (regenerate with STICKY_BLESS=1 cargo test --release --lib report::schema): {stale:?}"
    );
}
