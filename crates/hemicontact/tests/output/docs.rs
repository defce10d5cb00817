//! The user documentation (`docs/`) against the code.
//!
//! `docs/scenario.md` documents every key of a scenario file in tables whose rows read
//! `| `key.path` | type | unit | default | allowed |`, and shows examples in ```toml blocks.
//! These tests hold the reference to the code:
//!
//! - every ```toml block of `docs/` is a complete scenario that parses (unknown keys are
//!   refused) and validates (`Scenario::into_problem`, `Scenario::settings`);
//! - every key of the tables occurs in some example (so a misspelled key fails), and every
//!   key of the examples is in the tables (so none is undocumented);
//! - every setting of `SolverSettings` is documented, with the default of
//!   `SolverSettings::default()`;
//! - every other default written as a TOML literal is the one the scenario loader applies
//!   to the smallest example, which omits these keys;
//! - the relative links of the README and of `docs/` point to files that exist;
//! - the JSON Schema of the scenario file (`hemicontact schema`) has exactly the documented
//!   keys, accepts every committed scenario and every example, and refuses edits the loader
//!   refuses (checked by a small validator of the part of JSON Schema it uses).

use hemicontact::contact::friction::DEFAULT_REGULARIZATION;
use hemicontact::scenario::Scenario;
use hemicontact::solver::SolverSettings;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use toml::Value;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn read(relative: &str) -> String {
    let path = root().join(relative);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The ```toml blocks of a Markdown text, with the line of their opening fence.
fn toml_blocks(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for (k, line) in text.lines().enumerate() {
        match current.as_mut() {
            None if line.trim_start().starts_with("```toml") => {
                current = Some((k + 1, String::new()));
            }
            Some(_) if line.trim_start().starts_with("```") => {
                out.extend(current.take());
            }
            Some((_, body)) => {
                body.push_str(line);
                body.push('\n');
            }
            None => {}
        }
    }
    assert!(current.is_none(), "an unterminated ```toml block");
    out
}

/// One row of a key table: the key path, its default if written as a TOML literal, its line.
#[derive(Debug)]
struct Row {
    key: String,
    default: Option<Value>,
    line: usize,
}

/// The cells of a Markdown table row, split at unescaped `|`.
fn cells(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cell = String::new();
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'|') => {
                cell.push('|');
                chars.next();
            }
            '|' => out.push(std::mem::take(&mut cell).trim().to_string()),
            c => cell.push(c),
        }
    }
    out.push(cell.trim().to_string());
    out
}

/// A cell holding one `code` span, without the backticks.
fn code(cell: &str) -> Option<&str> {
    let inner = cell.strip_prefix('`')?.strip_suffix('`')?;
    (!inner.contains('`')).then_some(inner)
}

fn is_key_path(s: &str) -> bool {
    !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || "_.[]".contains(c))
}

/// The key tables of a Markdown text: rows whose first cell is a `key.path`.
fn key_rows(text: &str) -> Vec<Row> {
    let mut rows = Vec::new();
    for (k, line) in text.lines().enumerate() {
        if !line.starts_with('|') {
            continue;
        }
        let c = cells(line);
        let Some(key) = c
            .get(1)
            .and_then(|cell| code(cell))
            .filter(|k| is_key_path(k))
        else {
            continue;
        };
        // | key | type | unit | default | allowed |, with the empty cells outside the pipes.
        assert_eq!(
            c.len(),
            7,
            "line {}: a key row has the five columns key, type, unit, default, allowed",
            k + 1
        );
        let default = code(&c[4]).and_then(|lit| {
            toml::from_str::<toml::Table>(&format!("v = {lit}"))
                .ok()
                .and_then(|mut t| t.remove("v"))
        });
        rows.push(Row {
            key: key.to_string(),
            default,
            line: k + 1,
        });
    }
    rows
}

/// The values at `path` (`a.b[].c`: `[]` is every element of an array) in `v`.
fn lookup<'a>(v: &'a Value, path: &str) -> Vec<&'a Value> {
    let mut current = vec![v];
    for segment in path.split('.') {
        let (name, every) = match segment.strip_suffix("[]") {
            Some(name) => (name, true),
            None => (segment, false),
        };
        let mut next = Vec::new();
        for x in current {
            let Some(y) = x.as_table().and_then(|t| t.get(name)) else {
                continue;
            };
            match (every, y) {
                (true, Value::Array(items)) => next.extend(items.iter()),
                (true, _) => {}
                (false, y) => next.push(y),
            }
        }
        current = next;
    }
    current
}

/// The key paths of the leaves of `v` (arrays of tables as `name[]`).
fn leaves(v: &Value, prefix: &str, out: &mut BTreeSet<String>) {
    let join = |name: &str| {
        if prefix.is_empty() {
            name.to_string()
        } else {
            format!("{prefix}.{name}")
        }
    };
    match v {
        Value::Table(t) => {
            for (name, x) in t {
                match x {
                    Value::Table(_) => leaves(x, &join(name), out),
                    Value::Array(items)
                        if !items.is_empty() && items.iter().all(Value::is_table) =>
                    {
                        for item in items {
                            leaves(item, &format!("{}[]", join(name)), out);
                        }
                    }
                    _ => {
                        out.insert(join(name));
                    }
                }
            }
        }
        _ => {
            out.insert(prefix.to_string());
        }
    }
}

/// Equal values, numbers compared as numbers (`1000.0` and `1000`).
fn same(a: &Value, b: &Value) -> bool {
    let number = |v: &Value| match v {
        Value::Integer(i) => Some(*i as f64),
        Value::Float(x) => Some(*x),
        _ => None,
    };
    match (number(a), number(b)) {
        (Some(x), Some(y)) => x == y,
        _ => a == b,
    }
}

const DOCS_WITH_EXAMPLES: [&str; 2] = ["docs/scenario.md", "docs/model.md"];

/// The scenario of a ```toml block, its relative paths resolved against `scenarios/` (as
/// for the committed scenarios whose meshes the examples use).
fn scenario(doc: &str, line: usize, text: &str) -> Scenario {
    let mut s = Scenario::from_str(text, &format!("{doc}:{line}"))
        .unwrap_or_else(|e| panic!("{doc}, block at line {line}: {e}"));
    s.dir = Some(root().join("scenarios"));
    s
}

#[test]
fn every_toml_example_is_a_valid_scenario() {
    let mut n = 0;
    for doc in DOCS_WITH_EXAMPLES {
        for (line, text) in toml_blocks(&read(doc)) {
            let s = scenario(doc, line, &text);
            if let Err(e) = s.into_problem() {
                panic!("{doc}, block at line {line}: {e}");
            }
            if let Err(e) = s.settings() {
                panic!("{doc}, block at line {line}: {e}");
            }
            n += 1;
        }
    }
    assert!(n >= 5, "docs/scenario.md shows its examples ({n} found)");
}

#[test]
fn documented_keys_and_example_keys_are_the_same() {
    let text = read("docs/scenario.md");
    let rows = key_rows(&text);
    assert!(
        rows.len() > 50,
        "the key tables of docs/scenario.md ({} rows)",
        rows.len()
    );
    let mut documented = BTreeSet::new();
    for r in &rows {
        assert!(
            documented.insert(r.key.clone()),
            "docs/scenario.md:{}: `{}` documented twice",
            r.line,
            r.key
        );
    }
    let examples: Vec<(usize, Value)> = toml_blocks(&text)
        .into_iter()
        .map(|(line, body)| (line, toml::from_str(&body).expect("a TOML example")))
        .collect();
    for r in &rows {
        assert!(
            examples.iter().any(|(_, v)| !lookup(v, &r.key).is_empty()),
            "docs/scenario.md:{}: `{}` occurs in no example, so nothing shows the program \
             accepts it",
            r.line,
            r.key
        );
    }
    for (line, v) in &examples {
        let mut used = BTreeSet::new();
        leaves(v, "", &mut used);
        for key in used {
            assert!(
                documented.contains(&key),
                "docs/scenario.md, block at line {line}: `{key}` is not in the key tables"
            );
        }
    }
}

#[test]
fn documented_solver_defaults_are_the_code_defaults() {
    let rows = key_rows(&read("docs/scenario.md"));
    let defaults = Value::try_from(SolverSettings::default()).expect("settings as TOML");
    let mut keys = BTreeSet::new();
    leaves(&defaults, "solver", &mut keys);
    assert!(keys.len() >= 20, "the settings ({} found)", keys.len());
    for key in &keys {
        let row = rows
            .iter()
            .find(|r| &r.key == key)
            .unwrap_or_else(|| panic!("docs/scenario.md does not document `{key}`"));
        let code = lookup(&defaults, key.trim_start_matches("solver."))[0];
        let doc = row.default.as_ref().unwrap_or_else(|| {
            panic!(
                "docs/scenario.md:{}: the default of `{key}` is not a TOML literal (the code's \
                 is {code})",
                row.line
            )
        });
        assert!(
            same(doc, code),
            "docs/scenario.md:{}: `{key}` defaults to {code}, not {doc}",
            row.line
        );
    }
    for r in rows.iter().filter(|r| r.key.starts_with("solver.")) {
        assert!(
            r.default.is_none() || keys.contains(&r.key),
            "docs/scenario.md:{}: `{}` has a default but is no setting of SolverSettings",
            r.line,
            r.key
        );
    }
}

#[test]
fn documented_scenario_defaults_are_the_code_defaults() {
    let text = read("docs/scenario.md");
    let rows = key_rows(&text);
    let (line, smallest) = toml_blocks(&text).into_iter().next().expect("an example");
    let given: Value = toml::from_str(&smallest).expect("TOML");
    let s = scenario("docs/scenario.md", line, &smallest);
    s.into_problem().expect("the smallest example is valid");
    let resolved = Value::try_from(&s.file).expect("the scenario as TOML");
    let mut checked = 0;
    for r in rows.iter().filter(|r| !r.key.starts_with("solver.")) {
        let Some(doc) = &r.default else { continue };
        assert!(
            lookup(&given, &r.key).is_empty(),
            "docs/scenario.md:{}: the smallest example sets `{}`, so its default cannot be \
             checked on it",
            r.line,
            r.key
        );
        let code = match lookup(&resolved, &r.key).first() {
            Some(v) => (*v).clone(),
            // Optional keys whose default the loader applies when it builds the problem.
            None => match r.key.as_str() {
                "mesh.pattern" => Value::try_from(s.mesh_spec().expect("a mesh").pattern())
                    .expect("a pattern name"),
                "contact[].friction.regularization" => Value::Float(DEFAULT_REGULARIZATION),
                other => panic!(
                    "docs/scenario.md:{}: the default of `{other}` is not checked: add the \
                     key's parent table to the smallest example, or its default to this test",
                    r.line
                ),
            },
        };
        assert!(
            same(doc, &code),
            "docs/scenario.md:{}: `{}` defaults to {code}, not {doc}",
            r.line,
            r.key
        );
        checked += 1;
    }
    assert!(checked >= 10, "{checked} scenario defaults checked");
}

#[test]
fn relative_links_of_the_documentation_exist() {
    let mut docs = vec![PathBuf::from("README.md")];
    for entry in std::fs::read_dir(root().join("docs")).expect("docs/") {
        let path = entry.expect("an entry").path();
        if path.extension().is_some_and(|e| e == "md") {
            docs.push(Path::new("docs").join(path.file_name().expect("a name")));
        }
    }
    for doc in &docs {
        let text = read(&doc.to_string_lossy());
        let folder = doc.parent().unwrap_or(Path::new(""));
        for (k, line) in text.lines().enumerate() {
            for part in line.split("](").skip(1) {
                let target = part.split(')').next().unwrap_or("");
                let file = target.split('#').next().unwrap_or("");
                if file.is_empty() || file.contains("://") {
                    continue;
                }
                assert!(
                    root().join(folder).join(file).exists(),
                    "{}:{}: the link {target} points to no file",
                    doc.display(),
                    k + 1
                );
            }
        }
    }
}

/// The key paths of a JSON Schema (`a.b[].c` as in the key tables): every property, through
/// `items` of arrays (`name[]`) and the branches of `anyOf`/`oneOf`. Returns (all paths,
/// leaf paths: properties with no properties below them).
fn schema_keys(
    schema: &serde_json::Value,
    prefix: &str,
    all: &mut BTreeSet<String>,
    leaves: &mut BTreeSet<String>,
) {
    let mut branches = vec![schema];
    for key in ["anyOf", "oneOf"] {
        if let Some(list) = schema[key].as_array() {
            branches.extend(list.iter());
        }
    }
    for branch in branches {
        if !std::ptr::eq(branch, schema) {
            schema_keys(branch, prefix, all, leaves);
            continue;
        }
        if let Some(items) = branch.get("items") {
            if items.get("properties").is_some() {
                schema_keys(items, &format!("{prefix}[]"), all, leaves);
            }
        }
        let Some(props) = branch["properties"].as_object() else {
            continue;
        };
        for (name, sub) in props {
            let path = if prefix.is_empty() {
                name.clone()
            } else {
                format!("{prefix}.{name}")
            };
            all.insert(path.clone());
            let mut below = BTreeSet::new();
            schema_keys(sub, &path, all, &mut below);
            if below.is_empty() && !has_properties(sub) {
                leaves.insert(path);
            }
            leaves.extend(below);
        }
    }
}

/// Whether a schema describes a table (directly, through `items` or a branch).
fn has_properties(schema: &serde_json::Value) -> bool {
    schema.get("properties").is_some()
        || schema.get("items").is_some_and(has_properties)
        || ["anyOf", "oneOf"].iter().any(|k| {
            schema[*k]
                .as_array()
                .is_some_and(|l| l.iter().any(has_properties))
        })
}

#[allow(clippy::expect_used)]
fn json_schema() -> serde_json::Value {
    serde_json::from_str(hemicontact::scenario::JSON_SCHEMA).expect("the schema is JSON")
}

#[test]
fn json_schema_has_the_documented_keys() {
    let rows = key_rows(&read("docs/scenario.md"));
    let documented: BTreeSet<String> = rows.iter().map(|r| r.key.clone()).collect();
    let (mut all, mut leaves) = (BTreeSet::new(), BTreeSet::new());
    schema_keys(&json_schema(), "", &mut all, &mut leaves);
    assert!(
        leaves.len() > 50,
        "{} leaf keys in the schema",
        leaves.len()
    );
    for key in &documented {
        assert!(
            all.contains(key),
            "docs/scenario.md documents `{key}`, the JSON Schema has no such key"
        );
    }
    for key in &leaves {
        assert!(
            documented.contains(key),
            "the JSON Schema has `{key}`, docs/scenario.md does not document it"
        );
    }
}

/// Where `value` breaks `schema` (the subset of JSON Schema the scenario schema uses:
/// type, enum, const, properties, additionalProperties, required, items, minItems,
/// maxItems, anyOf, oneOf, minimum, maximum, exclusiveMinimum, exclusiveMaximum), or `None`.
fn violation(schema: &serde_json::Value, value: &serde_json::Value, at: &str) -> Option<String> {
    use serde_json::Value as J;
    let fail = |why: String| Some(format!("{at}: {why} ({value})"));
    if let Some(t) = schema["type"].as_str() {
        let ok = match t {
            "object" => value.is_object(),
            "array" => value.is_array(),
            "string" => value.is_string(),
            "boolean" => value.is_boolean(),
            "integer" => value.is_i64() || value.is_u64(),
            "number" => value.is_number(),
            other => panic!("type {other} not handled"),
        };
        if !ok {
            return fail(format!("not a {t}"));
        }
    }
    if let Some(e) = schema["enum"].as_array() {
        if !e.contains(value) {
            return fail(format!("not one of {e:?}"));
        }
    }
    if let Some(c) = schema.get("const") {
        if c != value {
            return fail(format!("not {c}"));
        }
    }
    if let Some(x) = value.as_f64() {
        let bound = |k: &str| schema[k].as_f64();
        if bound("minimum").is_some_and(|m| x < m)
            || bound("maximum").is_some_and(|m| x > m)
            || bound("exclusiveMinimum").is_some_and(|m| x <= m)
            || bound("exclusiveMaximum").is_some_and(|m| x >= m)
        {
            return fail("out of range".into());
        }
    }
    if let J::Object(map) = value {
        if let Some(req) = schema["required"].as_array() {
            for r in req {
                if !r.as_str().is_some_and(|r| map.contains_key(r)) {
                    return fail(format!("missing {r}"));
                }
            }
        }
        if let Some(props) = schema["properties"].as_object() {
            for (k, v) in map {
                match props.get(k) {
                    Some(sub) => {
                        if let Some(e) = violation(sub, v, &format!("{at}.{k}")) {
                            return Some(e);
                        }
                    }
                    None if schema["additionalProperties"] == J::Bool(false) => {
                        return fail(format!("unknown key {k}"));
                    }
                    None => {}
                }
            }
        }
    }
    if let J::Array(items) = value {
        let n = items.len() as u64;
        if schema["minItems"].as_u64().is_some_and(|m| n < m)
            || schema["maxItems"].as_u64().is_some_and(|m| n > m)
        {
            return fail("wrong length".into());
        }
        if let Some(sub) = schema.get("items") {
            for (k, item) in items.iter().enumerate() {
                if let Some(e) = violation(sub, item, &format!("{at}[{k}]")) {
                    return Some(e);
                }
            }
        }
    }
    if let Some(list) = schema["anyOf"].as_array() {
        if list.iter().all(|s| violation(s, value, at).is_some()) {
            return fail("matches no branch of anyOf".into());
        }
    }
    if let Some(list) = schema["oneOf"].as_array() {
        let matching = list
            .iter()
            .filter(|s| violation(s, value, at).is_none())
            .count();
        if matching != 1 {
            return fail(format!("matches {matching} branches of oneOf"));
        }
    }
    None
}

/// A TOML text as the JSON value an editor checks against the schema.
#[allow(clippy::expect_used)]
fn as_json(text: &str) -> serde_json::Value {
    let v: Value = toml::from_str(text).expect("TOML");
    serde_json::to_value(v).expect("TOML as JSON")
}

#[test]
fn json_schema_accepts_every_committed_scenario_and_example() {
    let schema = json_schema();
    let mut n = 0;
    for entry in std::fs::read_dir(root().join("scenarios")).expect("scenarios/") {
        let path = entry.expect("an entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            let text = std::fs::read_to_string(&path).expect("a scenario");
            if let Some(e) = violation(&schema, &as_json(&text), "") {
                panic!("{}: {e}", path.display());
            }
            n += 1;
        }
    }
    assert!(n >= 8, "{n} committed scenarios");
    for doc in DOCS_WITH_EXAMPLES {
        for (line, text) in toml_blocks(&read(doc)) {
            if let Some(e) = violation(&schema, &as_json(&text), "") {
                panic!("{doc}, block at line {line}: {e}");
            }
        }
    }
}

#[test]
fn json_schema_refuses_what_the_loader_refuses() {
    let schema = json_schema();
    let paper = read("scenarios/paper.toml");
    let edits = [
        ("young = 2000.0", "young = -1.0"),
        ("young = 2000.0", "young = 2000.0\nyoungs = 1.0"),
        ("bound = \"coulomb\"", "bound = \"amontons\""),
        ("beta = 100.0", "beta = 100.0, c = 1.0"),
        ("poisson = 0.3", "poisson = 0.5"),
        ("kind = \"rectangle\"", "kind = \"circle\""),
        (
            "kind = \"rectangle\"",
            "kind = \"rectangle\"\nprogression = [1.0, 0.0]",
        ),
    ];
    for (from, to) in edits {
        let text = paper.replacen(from, to, 1);
        assert!(
            Scenario::from_str(&text, "edit")
                .and_then(|s| s.into_problem().map(|_| ()))
                .is_err(),
            "the loader accepts {to}"
        );
        assert!(
            violation(&schema, &as_json(&text), "").is_some(),
            "the schema accepts {to}"
        );
    }
    // The shorthand for a constant coefficient passes both.
    let text = paper.replace(
        "mu = { law = \"exponential\", a = 0.4, b = 0.1, beta = 100.0 }",
        "mu = 0.3",
    );
    assert!(text.contains("mu = 0.3"));
    Scenario::from_str(&text, "shorthand")
        .unwrap()
        .into_problem()
        .unwrap();
    assert_eq!(violation(&schema, &as_json(&text), ""), None);
}

/// The source files of a folder (recursively), relative to it.
fn rust_files(dir: &Path, base: &Path, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, base, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(
                path.strip_prefix(base)
                    .unwrap()
                    .to_string_lossy()
                    .replace('\\', "/"),
            );
        }
    }
}

/// ARCHITECTURE.md names every module: each source file of the library by its file name
/// (a folder's `mod.rs` by its folder), so that a newcomer finds every room of the house
/// there. Unit-test files (`tests.rs`) and `lib.rs` are the exceptions.
#[test]
fn architecture_names_every_module() {
    let text = read("ARCHITECTURE.md");
    let src = root().join("crates/hemicontact/src");
    let mut files = Vec::new();
    rust_files(&src, &src, &mut files);
    files.sort();
    assert!(
        files.len() > 100,
        "{} source files found under {src:?}",
        files.len()
    );
    let missing: Vec<&String> = files
        .iter()
        .filter(|f| {
            let p = Path::new(f.as_str());
            let name = p.file_name().unwrap().to_string_lossy().to_string();
            let shown = match name.as_str() {
                "lib.rs" | "tests.rs" => return false,
                "mod.rs" => format!(
                    "{}/",
                    p.parent().unwrap().file_name().unwrap().to_string_lossy()
                ),
                _ => name,
            };
            !text.contains(&format!("`{shown}`")) && !text.contains(&format!("{shown}`"))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md does not name {missing:?}"
    );
}
