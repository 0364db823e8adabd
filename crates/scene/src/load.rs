//! Loading scenes from TOML: syntax check, `base` preset inheritance by deep merge, unknown
//! field detection, per-field type errors and validation, all reported together with
//! `origin:line:column` positions.

use std::ops::Range;
use std::path::Path;

use toml::de::{DeTable, DeValue};
use toml::{Table, Value};

use crate::error::{Location, Problem, ProblemKind, SceneError};
use crate::presets;
use crate::scene::Scene;
use crate::text::{nearest, quote, toml_value};
use crate::validate;

/// Top-level keys that are not part of [`Scene`]: `base` (preset to inherit) and
/// `description` (one line of prose).
const META_KEYS: [&str; 2] = ["base", "description"];

/// How deep `base` chains may go (guards against cycles among presets).
const MAX_BASE_DEPTH: usize = 8;

impl Scene {
    /// Parses a scene from TOML text.
    ///
    /// The text is partial: it states only what differs from its base, the preset named by a
    /// top-level `base = "NAME"` key (default: `cumulus-noon`, i.e. [`Scene::default`]). The
    /// base's tables are deep-merged with the text's (the text wins), then deserialized and
    /// validated. `origin` (usually the file path) prefixes every message.
    ///
    /// All problems are reported at once: syntax errors (`origin:line:col: message`), unknown
    /// fields (with the nearest valid name), values of the wrong type and broken validation
    /// rules (`path = value: rule`).
    pub fn from_toml_str(src: &str, origin: &str) -> Result<Scene, SceneError> {
        Loader::new(src, origin).load()
    }

    /// Reads and parses a scene file (see [`Scene::from_toml_str`]); messages start with the
    /// path as given.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let origin = path.display().to_string();
        match std::fs::read_to_string(path) {
            Ok(src) => Self::from_toml_str(&src, &origin),
            Err(e) => {
                let mut problem =
                    Problem::new(ProblemKind::Io, None, format!("cannot read the file: {e}"));
                problem.origin = Some(origin);
                Err(SceneError::new(vec![problem]))
            }
        }
    }

    /// The built-in preset called `name` (see [`presets`](crate::presets)). An unknown name is
    /// an error that lists the presets and suggests the nearest one.
    pub fn preset(name: &str) -> Result<Scene, SceneError> {
        match presets::source(name) {
            Some(src) => Self::from_toml_str(src, &format!("<preset {name}>")),
            None => Err(SceneError::new(vec![Problem::new(
                ProblemKind::UnknownPreset,
                None,
                unknown_preset_message(name),
            )])),
        }
    }

    /// The whole scene as TOML: every section and field, defaults filled in (optional fields
    /// that are unset are left out). [`Scene::from_toml_str`] reads it back to an equal scene.
    ///
    /// # Panics
    ///
    /// If `noise.seed` exceeds `i64::MAX`, which TOML cannot represent ([`Scene::validate`]
    /// reports it; a scene read from TOML can never have it).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("a scene always serializes to TOML (noise.seed <= i64::MAX)")
    }

    /// Checks every field against its rule (finite numbers, ranges, `cloud_bottom_m <
    /// cloud_top_m`, non-zero directions, ...) and reports every broken rule, each as
    /// `path = value: rule`.
    pub fn validate(&self) -> Result<(), SceneError> {
        let problems: Vec<Problem> = validate::check(self)
            .into_iter()
            .map(|issue| issue.into_problem(false))
            .collect();
        if problems.is_empty() {
            Ok(())
        } else {
            Err(SceneError::new(problems))
        }
    }
}

/// `; did you mean "x"? (available: ...)`, the end of an unknown-preset message.
fn preset_hint(name: &str) -> String {
    let names = presets::names();
    let available = names.join(", ");
    match nearest(name, &names) {
        Some(s) => format!("; did you mean {}? (available: {available})", quote(s)),
        None => format!(" (available: {available})"),
    }
}

/// `unknown preset "x"; did you mean ...`.
fn unknown_preset_message(name: &str) -> String {
    format!("unknown preset {}{}", quote(name), preset_hint(name))
}

/// The merged TOML table of the preset `name`, its own `base` chain resolved.
fn preset_table(name: &str, depth: usize) -> Result<Table, String> {
    let src = presets::source(name).ok_or_else(|| unknown_preset_message(name))?;
    let mut table: Table =
        toml::from_str(src).map_err(|e| format!("preset {name} is malformed: {}", e.message()))?;
    table.remove("description");
    match table.remove("base") {
        None => Ok(table),
        Some(Value::String(base)) if depth < MAX_BASE_DEPTH => {
            let mut merged = preset_table(&base, depth + 1)
                .map_err(|e| format!("in the base of preset {name}: {e}"))?;
            merge(&mut merged, table);
            Ok(merged)
        }
        Some(_) => Err(format!(
            "preset {name} has an invalid or too deeply nested base"
        )),
    }
}

/// Deep merge: tables merge key by key, anything else in `over` replaces the value in `base`.
fn merge(base: &mut Table, over: Table) {
    for (key, value) in over {
        match (base.get_mut(&key), value) {
            (Some(Value::Table(b)), Value::Table(o)) => merge(b, o),
            (_, value) => {
                base.insert(key, value);
            }
        }
    }
}

/// Where a key and its value are in the source.
struct Spans {
    key: Range<usize>,
    value: Range<usize>,
}

/// Finds `path` in the spanned parse of the source.
fn lookup(table: &DeTable<'_>, path: &[&str]) -> Option<Spans> {
    let (first, rest) = path.split_first()?;
    let (key, value) = table.iter().find(|(k, _)| k.get_ref().as_ref() == *first)?;
    if rest.is_empty() {
        Some(Spans {
            key: key.span(),
            value: value.span(),
        })
    } else {
        match value.get_ref() {
            DeValue::Table(t) => lookup(t, rest),
            _ => None,
        }
    }
}

/// One load: the source, its spanned parse and the problems found so far.
struct Loader<'a> {
    src: &'a str,
    origin: &'a str,
    spanned: Option<DeTable<'a>>,
    problems: Vec<Problem>,
    /// Paths whose values had the wrong type (and were replaced by defaults).
    bad_paths: Vec<String>,
}

impl<'a> Loader<'a> {
    fn new(src: &'a str, origin: &'a str) -> Self {
        Self {
            src,
            origin,
            spanned: None,
            problems: Vec::new(),
            bad_paths: Vec::new(),
        }
    }

    fn load(mut self) -> Result<Scene, SceneError> {
        let (spanned, errors) = DeTable::parse_recoverable(self.src);
        if !errors.is_empty() {
            for e in errors {
                self.syntax(&e);
            }
            // After an error the parser resynchronises at the next line; later errors on the
            // same line are consequences of the first.
            self.problems.sort_by_key(|p| p.location);
            self.problems.dedup_by_key(|p| p.location.map(|l| l.line));
            return Err(self.finish());
        }
        self.spanned = Some(spanned.into_inner());
        let mut file: Table = match toml::from_str(self.src) {
            Ok(t) => t,
            Err(e) => {
                self.syntax(&e);
                return Err(self.finish());
            }
        };

        let base = self.base(&mut file);
        if let Some(description) = file.remove("description") {
            if !description.is_str() {
                self.report_at_value(
                    ProblemKind::WrongType,
                    &["description"],
                    format!(
                        "description = {}: must be a string",
                        toml_value(&description)
                    ),
                );
            }
        }

        let schema = Table::try_from(Scene::schema()).expect("the schema scene serializes");
        self.prune_unknown(&mut file, &schema, &schema, &[]);

        let mut merged = base;
        merge(&mut merged, file);
        let scene = self.deserialize(merged, &schema);

        let mut invalid = Vec::new();
        for issue in validate::check(&scene) {
            // A value of the wrong type was replaced by its default: don't judge that default.
            let broken = |p: &str| self.bad_paths.iter().any(|b| b == p);
            if broken(issue.path) || issue.related.as_ref().is_some_and(|(r, _)| broken(r)) {
                continue;
            }
            let related_span = issue.related.as_ref().and_then(|(r, _)| self.value_span(r));
            let (span, from_related_side) = match self.value_span(issue.path) {
                Some(span) => (Some(span), false),
                None => (related_span.clone(), related_span.is_some()),
            };
            let mut problem = issue.into_problem(from_related_side);
            problem.origin = Some(self.origin.to_owned());
            problem.location = span.map(|s| Location::from_offset(self.src, s.start));
            invalid.push(problem);
        }
        self.problems.extend(invalid);

        if self.problems.is_empty() {
            Ok(scene)
        } else {
            Err(self.finish())
        }
    }

    /// Removes `base` from the file and returns the merged table of that preset (empty for the
    /// default, whose values are the Rust defaults).
    fn base(&mut self, file: &mut Table) -> Table {
        let name = match file.remove("base") {
            None => return Table::new(),
            Some(Value::String(name)) => name,
            Some(other) => {
                self.report_at_value(
                    ProblemKind::WrongType,
                    &["base"],
                    format!(
                        "base = {}: must be the name of a preset (a string; available: {})",
                        toml_value(&other),
                        presets::names().join(", ")
                    ),
                );
                return Table::new();
            }
        };
        if presets::source(&name).is_none() {
            let message = format!(
                "base = {}: unknown preset{}",
                quote(&name),
                preset_hint(&name)
            );
            self.report_at_value(ProblemKind::UnknownPreset, &["base"], message);
            return Table::new();
        }
        match preset_table(&name, 0) {
            Ok(table) => table,
            Err(rule) => {
                let message = format!("base = {}: {rule}", quote(&name));
                self.report_at_value(ProblemKind::InvalidValue, &["base"], message);
                Table::new()
            }
        }
    }

    /// Reports and removes every key of `table` that `schema` does not know (and every
    /// non-table where a section belongs); recurses into sections.
    fn prune_unknown(&mut self, table: &mut Table, schema: &Table, root: &Table, path: &[&str]) {
        let keys: Vec<String> = table.keys().cloned().collect();
        for key in keys {
            let mut full: Vec<&str> = path.to_vec();
            full.push(&key);
            let dotted = full.join(".");
            match schema.get(&key) {
                None => {
                    let message = unknown_field_message(&key, path, schema, root);
                    self.report_at_key(ProblemKind::UnknownField, &full, message);
                    table.remove(&key);
                }
                Some(Value::Table(sub_schema)) => match table.get_mut(&key) {
                    Some(Value::Table(sub)) => self.prune_unknown(sub, sub_schema, root, &full),
                    Some(other) => {
                        let message = format!(
                            "{dotted} = {}: must be a table (a [{dotted}] section)",
                            toml_value(other)
                        );
                        self.report_at_value(ProblemKind::WrongType, &full, message);
                        table.remove(&key);
                    }
                    None => unreachable!("key taken from the table"),
                },
                Some(_) => {}
            }
        }
    }

    /// Deserializes the merged table. A value of the wrong type is reported, removed (its
    /// default takes its place) and the rest is still deserialized, so that every such value
    /// is found and the other fields are still validated.
    fn deserialize(&mut self, mut merged: Table, schema: &Table) -> Scene {
        if let Ok(scene) = Value::Table(merged.clone()).try_into::<Scene>() {
            return scene;
        }
        let mut leaves = Vec::new();
        collect_leaves(&merged, schema, &mut Vec::new(), &mut leaves);
        for (path, value) in leaves {
            let Err(e) = Value::Table(nest(&path, value.clone())).try_into::<Scene>() else {
                continue;
            };
            let path_refs: Vec<&str> = path.iter().map(String::as_str).collect();
            let dotted = path.join(".");
            let rule = expected_rule(schema_leaf(schema, &path_refs), &value, &path, e.message());
            self.report_at_value(
                ProblemKind::WrongType,
                &path_refs,
                format!("{dotted} = {}: {rule}", toml_value(&value)),
            );
            self.bad_paths.push(dotted);
            remove_path(&mut merged, &path_refs);
        }
        match Value::Table(merged).try_into::<Scene>() {
            Ok(scene) => scene,
            Err(e) => {
                // Not expected: every failing leaf was removed above.
                self.report(ProblemKind::WrongType, None, None, e.message().to_owned());
                Scene::default()
            }
        }
    }

    fn syntax(&mut self, e: &toml::de::Error) {
        let span = e.span();
        let mut message = e.message().trim().replace('\n', "; ");
        // toml says "duplicate key" without naming it; the span covers the key.
        if message == "duplicate key" {
            if let Some(key) = span.clone().and_then(|s| self.src.get(s)) {
                message = format!("duplicate key {}", key.trim());
            }
        }
        self.report(ProblemKind::Syntax, None, span, message);
    }

    fn value_span(&self, dotted: &str) -> Option<Range<usize>> {
        let path: Vec<&str> = dotted.split('.').collect();
        lookup(self.spanned.as_ref()?, &path).map(|s| s.value)
    }

    fn report_at_key(&mut self, kind: ProblemKind, path: &[&str], message: String) {
        let span = self
            .spanned
            .as_ref()
            .and_then(|t| lookup(t, path))
            .map(|s| s.key);
        self.report(kind, Some(path.join(".")), span, message);
    }

    fn report_at_value(&mut self, kind: ProblemKind, path: &[&str], message: String) {
        let span = self
            .spanned
            .as_ref()
            .and_then(|t| lookup(t, path))
            .map(|s| s.value);
        self.report(kind, Some(path.join(".")), span, message);
    }

    fn report(
        &mut self,
        kind: ProblemKind,
        path: Option<String>,
        span: Option<Range<usize>>,
        message: String,
    ) {
        let mut problem = Problem::new(kind, path, message);
        problem.origin = Some(self.origin.to_owned());
        problem.location = span.map(|s| Location::from_offset(self.src, s.start));
        self.problems.push(problem);
    }

    /// The error, problems ordered by position (unpositioned ones last, in order found).
    fn finish(mut self) -> SceneError {
        self.problems
            .sort_by_key(|p| (p.location.is_none(), p.location));
        SceneError::new(self.problems)
    }
}

/// `unknown field clouds.covrage; did you mean clouds.coverage?`, or a list of the valid names
/// when nothing is close.
fn unknown_field_message(key: &str, path: &[&str], schema: &Table, root: &Table) -> String {
    let prefix: String = path.iter().map(|p| format!("{p}.")).collect();
    let mut candidates: Vec<&str> = schema.keys().map(String::as_str).collect();
    if path.is_empty() {
        candidates.extend(META_KEYS);
    }
    let unknown = format!("unknown field {prefix}{key}");
    if let Some(s) = nearest(key, &candidates) {
        return format!("{unknown}; did you mean {prefix}{s}?");
    }
    // The right name in the wrong section (e.g. `coverage` at the top level)?
    let mut elsewhere = Vec::new();
    find_key(root, key, &mut Vec::new(), &mut elsewhere);
    if !elsewhere.is_empty() {
        return format!("{unknown}; did you mean {}?", elsewhere.join(" or "));
    }
    let what = if path.is_empty() {
        "sections"
    } else {
        "fields"
    };
    format!("{unknown}; valid {what}: {}", candidates.join(", "))
}

/// Dotted paths of every key in `table` (at any depth) spelled `key` (ignoring case, `-`/`_`).
fn find_key(table: &Table, key: &str, path: &mut Vec<String>, out: &mut Vec<String>) {
    let norm = |s: &str| s.to_lowercase().replace('-', "_");
    for (k, v) in table {
        path.push(k.clone());
        if norm(k) == norm(key) {
            out.push(path.join("."));
        }
        if let Value::Table(t) = v {
            find_key(t, key, path, out);
        }
        path.pop();
    }
}

/// Every non-section value of `table` with its path (recursing into sections of `schema`).
fn collect_leaves(
    table: &Table,
    schema: &Table,
    path: &mut Vec<String>,
    out: &mut Vec<(Vec<String>, Value)>,
) {
    for (key, value) in table {
        path.push(key.clone());
        match (value, schema.get(key)) {
            (Value::Table(t), Some(Value::Table(s))) => collect_leaves(t, s, path, out),
            _ => out.push((path.clone(), value.clone())),
        }
        path.pop();
    }
}

/// `{a = {b = value}}` for path `[a, b]`.
fn nest(path: &[String], value: Value) -> Table {
    let mut value = value;
    for key in path.iter().skip(1).rev() {
        let mut t = Table::new();
        t.insert(key.clone(), value);
        value = Value::Table(t);
    }
    let mut root = Table::new();
    root.insert(path[0].clone(), value);
    root
}

fn remove_path(table: &mut Table, path: &[&str]) {
    match path {
        [] => {}
        [last] => {
            table.remove(*last);
        }
        [first, rest @ ..] => {
            if let Some(Value::Table(t)) = table.get_mut(*first) {
                remove_path(t, rest);
            }
        }
    }
}

fn schema_leaf<'s>(schema: &'s Table, path: &[&str]) -> Option<&'s Value> {
    let (first, rest) = path.split_first()?;
    let value = schema.get(*first)?;
    if rest.is_empty() {
        Some(value)
    } else {
        schema_leaf(value.as_table()?, rest)
    }
}

/// What a value at a field should have been, from the field's type in the schema.
fn expected_rule(schema: Option<&Value>, value: &Value, path: &[String], serde: &str) -> String {
    match schema {
        Some(Value::Float(_)) => "must be a number".to_owned(),
        Some(Value::Integer(_)) => match value {
            Value::Integer(i) if *i < 0 => "must be a whole number >= 0".to_owned(),
            Value::Integer(_) if serde.contains("u32") => {
                format!("must be a whole number <= {}", u32::MAX)
            }
            _ => "must be a whole number".to_owned(),
        },
        Some(Value::Boolean(_)) => "must be true or false".to_owned(),
        Some(Value::String(_)) => {
            let names = variant_names(path);
            if names.is_empty() {
                return serde.to_owned();
            }
            let list: Vec<String> = names.iter().map(|n| quote(n)).collect();
            let mut rule = format!("must be one of {}", list.join(", "));
            if let Some(s) = value.as_str() {
                let refs: Vec<&str> = names.iter().map(String::as_str).collect();
                if let Some(near) = nearest(s, &refs) {
                    rule.push_str(&format!("; did you mean {}?", quote(near)));
                }
            }
            rule
        }
        Some(Value::Array(a)) => {
            let what = match a.first() {
                Some(Value::Integer(_)) => "whole numbers >= 0".to_owned(),
                _ => "numbers".to_owned(),
            };
            format!("must be an array of {} {what}", a.len())
        }
        _ => serde.to_owned(),
    }
}

/// The TOML spellings of the enum at `path`, read from serde's "unknown variant" message.
fn variant_names(path: &[String]) -> Vec<String> {
    let probe = Value::Table(nest(path, Value::String("\u{1}".to_owned())));
    let Err(e) = probe.try_into::<Scene>() else {
        return Vec::new();
    };
    let message = e.message();
    let Some((_, expected)) = message.split_once("expected") else {
        return Vec::new();
    };
    expected
        .split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}
