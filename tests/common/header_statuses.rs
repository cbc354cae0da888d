//! The statuses each function of `include/orient.h` may return, derived from the
//! header's own text, so that a check against them holds the library to what its header
//! says (issue 40: "every function returns only statuses its header sentence lists").
//!
//! A function may return:
//! - `OK`;
//! - every status its doc comment names, as `ORIENT_STATUS_X` or as the short `X`;
//! - `NULL_POINTER` when it has a pointer argument (the header's "Errors" paragraph);
//! - `INVALID_HANDLE` when it has an `OrientFilter` argument, not an out-pointer to one
//!   (the "Handles" paragraph);
//! - the statuses of a function its doc defers to: "as orient_x", "as with orient_x",
//!   or a doc that opens with a call, "orient_x(...): ...";
//! - a status whose enum doc attributes it to the function ("orient_filter_save: ...");
//! - the statuses the `OrientConfig` struct doc names, for a function that takes one
//!   (not the `*_default` functions, which write one);
//! - `INVALID_ARGUMENT` ("an enum value, flag bit or index that the library does not
//!   know") for a function with such an argument: a kind, sensor or index number, a
//!   configuration (its frame and init) or samples (their flags);
//! - `UNKNOWN_PARAM` and `PARAM_OUT_OF_RANGE` (their enum docs: "no parameter with that
//!   id", "a parameter value ... outside its documented range") for a function with a
//!   parameter `id` and value;
//! - for the calls that update from samples (`UPDATE_LIKE`): the statuses of
//!   the statuses orient_filter_update's doc names and every status whose enum doc is
//!   about a sample, a reading or dt (not those about an output).
//!
//! Shared by the fuzz target (fuzz/fuzz_targets/abi_calls.rs) and
//! tests/header_statuses.rs, which prints the table for a reader to check.

use std::collections::{BTreeMap, BTreeSet};

/// Calls that update filters from samples.
pub const UPDATE_LIKE: &[&str] = &[
    "orient_filter_update",
    "orient_filter_update_batch",
    "orient_filter_update_arrays",
    "orient_filters_update",
    "orient_smooth_arrays",
];

/// One function of the header.
#[derive(Debug, Default, Clone)]
pub struct Function {
    pub doc: String,
    pub args: Vec<String>,
    /// Allowed status (short name) -> the rules that allow it.
    pub allowed: BTreeMap<String, Vec<&'static str>>,
}

/// The header's statuses and the allowed set of each function returning OrientStatus.
#[derive(Debug, Default)]
pub struct Table {
    /// Status number -> short name (`NULL_POINTER`) and its enum doc.
    pub statuses: BTreeMap<i32, (String, String)>,
    pub functions: BTreeMap<String, Function>,
}

fn words(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).filter(|w| !w.is_empty())
}

fn clean_doc(raw: &str) -> String {
    raw.lines()
        .map(|l| l.trim().trim_start_matches('*').trim())
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
}

impl Table {
    pub fn parse(header: &str) -> Table {
        let mut t = Table::default();
        let mut config_doc = String::new();
        let mut rest = header;
        while let Some(i) = rest.find("/**") {
            let after = &rest[i + 3..];
            let Some(j) = after.find("*/") else { break };
            let doc = clean_doc(&after[..j]);
            let tail = after[j + 2..].trim_start();
            if let Some(decl) = tail.strip_prefix("OrientStatus ") {
                let decl = &decl[..decl.find(';').unwrap_or(decl.len())];
                let open = decl.find('(').expect("a function declaration");
                let name = decl[..open].trim().to_string();
                let close = decl.rfind(')').expect("a function declaration");
                let args = decl[open + 1..close]
                    .split(',')
                    .map(|a| a.split_whitespace().collect::<Vec<_>>().join(" "));
                let f = Function { doc, args: args.collect(), allowed: BTreeMap::new() };
                t.functions.insert(name, f);
            } else if let Some(entry) = tail.strip_prefix("ORIENT_STATUS_") {
                let entry = &entry[..entry.find(',').unwrap_or(entry.len())];
                let (name, number) = entry.split_once('=').expect("ORIENT_STATUS_X = n");
                let number: i32 = number.trim().parse().expect("a status number");
                t.statuses.insert(number, (name.trim().to_string(), doc));
            } else if tail.starts_with("typedef struct OrientConfig ") {
                config_doc = doc;
            }
            rest = &after[j + 2..];
        }
        assert!(t.statuses.len() > 10 && t.functions.len() > 30, "the header did not parse");
        let names: BTreeSet<String> = t.statuses.values().map(|(n, _)| n.clone()).collect();
        let named = |text: &str| -> BTreeSet<String> {
            words(text)
                .map(|w| w.strip_prefix("ORIENT_STATUS_").unwrap_or(w))
                .filter(|w| names.contains(*w))
                .map(str::to_string)
                .collect()
        };
        let function_names: Vec<String> = t.functions.keys().cloned().collect();
        // Own rules first; deferrals and update-likes read the result.
        for (name, f) in t.functions.iter_mut() {
            let mut allow =
                |s: &str, why: &'static str| f.allowed.entry(s.to_string()).or_default().push(why);
            allow("OK", "always");
            for s in named(&f.doc) {
                allow(&s, "named in its doc");
            }
            if f.args.iter().any(|a| a.contains('*')) {
                allow("NULL_POINTER", "pointer argument");
            }
            if f.args.iter().any(|a| a.contains("OrientFilter") && !a.contains("**")) {
                allow("INVALID_HANDLE", "OrientFilter argument");
            }
            let config_in = |a: &String| a.contains("struct OrientConfig") && !name.ends_with("_default");
            if f.args.iter().any(config_in) {
                for s in named(&config_doc) {
                    allow(&s, "OrientConfig's struct doc");
                }
            }
            let enum_like = |a: &String| {
                a.ends_with(" kind")
                    || a.ends_with(" sensor")
                    || a.ends_with(" index")
                    || config_in(a)
                    || a.contains("struct OrientSample")
            };
            if f.args.iter().any(enum_like) {
                allow("INVALID_ARGUMENT", "enum, index or flags argument");
            }
            if f.args.iter().any(|a| a == "uint32_t id") {
                allow("UNKNOWN_PARAM", "parameter id argument");
                allow("PARAM_OUT_OF_RANGE", "parameter id argument");
            }
            for (status, doc) in t.statuses.values() {
                if doc.contains(&format!("{name}:")) {
                    allow(status, "the status's doc names it");
                }
            }
        }
        // Deferrals: "as orient_x", "as with orient_x", a doc opening with "orient_x(".
        let mut deferred: Vec<(String, String)> = Vec::new();
        for (name, f) in &t.functions {
            let ws: Vec<&str> = words(&f.doc).collect();
            for (k, w) in ws.iter().enumerate() {
                let after_as =
                    k > 0 && (ws[k - 1] == "as" || (k > 1 && ws[k - 2] == "as" && ws[k - 1] == "with"));
                let opening = k == 0 && f.doc.starts_with(&format!("{w}("));
                if (after_as || opening) && function_names.iter().any(|n| n == w) && *w != name {
                    deferred.push((name.clone(), w.to_string()));
                }
            }
        }
        for (name, target) in deferred {
            let from: Vec<String> = t.functions[&target].allowed.keys().cloned().collect();
            let f = t.functions.get_mut(&name).unwrap();
            for s in from {
                f.allowed.entry(s).or_default().push("deferred to another function");
            }
        }
        // Update-likes: orient_filter_update's set and the enum's sample statuses.
        let update: Vec<String> = t.functions["orient_filter_update"]
            .allowed
            .iter()
            .filter(|(_, why)| why.contains(&"named in its doc"))
            .map(|(s, _)| s.clone())
            .collect();
        let sample_words = ["sample", "samples", "reading", "readings", "dt"];
        let about_samples: Vec<String> = t
            .statuses
            .values()
            .filter(|(_, doc)| {
                !doc.starts_with("The output") && words(doc).any(|w| sample_words.contains(&w))
            })
            .map(|(n, _)| n.clone())
            .collect();
        for name in UPDATE_LIKE {
            let f = t.functions.get_mut(*name).expect("an update-like function");
            for s in &update {
                f.allowed.entry(s.clone()).or_default().push("update-like: orient_filter_update's");
            }
            for s in &about_samples {
                f.allowed.entry(s.clone()).or_default().push("update-like: enum doc about samples");
            }
        }
        for f in t.functions.values_mut() {
            for why in f.allowed.values_mut() {
                why.dedup();
            }
        }
        t
    }

    /// The short name of status number `status`.
    pub fn name(&self, status: i32) -> &str {
        self.statuses.get(&status).map(|(n, _)| n.as_str()).unwrap_or("(not a status)")
    }

    /// Whether the header lets `function` return status number `status`.
    pub fn allows(&self, function: &str, status: i32) -> bool {
        let f = self.functions.get(function).unwrap_or_else(|| panic!("{function} is not in the header"));
        f.allowed.contains_key(self.name(status))
    }

    /// The table, one function a line, for a reader to check against the header.
    pub fn render(&self) -> String {
        let mut out = String::new();
        for (name, f) in &self.functions {
            let set: Vec<String> =
                f.allowed.iter().map(|(s, why)| format!("{s} [{}]", why.join("; "))).collect();
            out += &format!("{name}:\n    {}\n", set.join("\n    "));
        }
        out
    }
}
