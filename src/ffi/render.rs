//! The generated files of the C API, rendered from the core's tables, and the tests that
//! hold the committed files to them: `param_ids.rs` (each kind's `settings!`,
//! `params::COMMON` and the slot map `params::BLOCKS`), `bits.rs` (the `bits!` tables
//! of `filters::flags` and `filters::diag`) and `joint_settings.rs` (orient_config_for_joints,
//! its doc from `joints::SENSOR_SETTINGS`). cbindgen reads the committed files into
//! include/orient.h, from which the C# and Python layers are generated in turn, so a
//! value or a doc sentence is written once, in the core. With ORIENT_BLESS=1 the tests
//! write the files instead.

use crate::filters::flags::BitSpec;
use crate::filters::params::{self, ParamSpec, BLOCKS, COMMON};
use crate::filters::{diag, flags, Kind};
use std::fmt::Write;

/// `text` in lines of at most 86 characters (90 with the comment marker).
fn wrap(text: &str) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in text.split_whitespace() {
        let last = lines.last_mut().expect("one line");
        if !last.is_empty() && last.len() + 1 + word.len() > 86 {
            lines.push(word.to_string());
        } else {
            if !last.is_empty() {
                last.push(' ');
            }
            last.push_str(word);
        }
    }
    lines
}

fn doc_comment(out: &mut String, text: &str) {
    for line in wrap(text) {
        let _ = writeln!(out, "/// {line}");
    }
}

/// The C name of the parameter named `name`: ORIENT_PARAM_NAME for a common one,
/// ORIENT_PARAM_KIND_NAME for one kind's, ORIENT_PARAM_*_NAME where several kinds have
/// one of that name.
fn c_param(name: &str) -> Option<String> {
    let upper = name.to_ascii_uppercase();
    if COMMON.iter().any(|p| p.name == name) {
        return Some(format!("ORIENT_PARAM_{upper}"));
    }
    let kinds: Vec<Kind> =
        Kind::ALL.into_iter().filter(|k| k.params().skip(COMMON.len()).any(|p| p.name == name)).collect();
    match kinds[..] {
        [] => None,
        [kind] => Some(format!("ORIENT_PARAM_{}_{upper}", kind.name().to_ascii_uppercase())),
        _ => Some(format!("ORIENT_PARAM_*_{upper}")),
    }
}

/// A bit's doc as the header says it: `` [`NAME`] `` becomes the C constant of that bit
/// of `table`, a parameter name in backticks its ORIENT_PARAM_* constant, and the text
/// follows `what` (the C item the bit belongs to).
fn c_doc(bit: &BitSpec, table: &[BitSpec], c_prefix: &str, what: &str) -> String {
    let mut text = bit.doc.split_whitespace().collect::<Vec<_>>().join(" ");
    for other in table {
        text = text.replace(&format!("[`{}`]", other.name), &format!("{c_prefix}{}", other.name));
    }
    assert!(!text.contains("[`"), "{}: a link to no bit of its table: {text}", bit.name);
    let mut out = String::new();
    for (i, piece) in text.split('`').enumerate() {
        match (i % 2, c_param(piece)) {
            (1, Some(c)) => out.push_str(&c),
            (1, None) => {
                out.push('`');
                out.push_str(piece);
                out.push('`');
            }
            _ => out.push_str(piece),
        }
    }
    // "The filter has ..." reads "`orient_filter_flags`: the filter has ..." (a name
    // such as "GMVDK" or "McGinnis" keeps its capitals).
    let first_word = out.split(' ').next().unwrap_or("");
    if first_word.chars().skip(1).all(|c| c.is_ascii_lowercase()) {
        out[..1].make_ascii_lowercase();
    }
    format!("{what}: {out}")
}

/// The text of `src/ffi/bits.rs`.
pub(crate) fn render_bits() -> String {
    let mut out = String::from(
        "//! Flag and diagnostics bits for C. Generated from the core's tables (the `bits!` tables\n\
         //! of `filters::flags` and `filters::diag`) by the test `bits_are_generated_from_the_tables`\n\
         //! in `src/ffi/render.rs`; do not edit. Regenerate: ORIENT_BLESS=1 cargo test -p orient --lib\n\
         //! generated_from_the_tables\n",
    );
    let tables: [(&[BitSpec], &str, &str); 2] = [
        (flags::TABLE, "ORIENT_FLAG_", "`orient_filter_flags`"),
        (diag::TABLE, "ORIENT_DIAG_", "OrientDiagnostics.present"),
    ];
    for (table, c_prefix, what) in tables {
        out.push('\n');
        for bit in table {
            doc_comment(&mut out, &c_doc(bit, table, c_prefix, what));
            let _ = writeln!(out, "pub const {c_prefix}{}: u32 = {};", bit.name, bit.value);
        }
    }
    out
}

/// The documentation of ORIENT_MAX_PARAMS: the slot map, from `params::BLOCKS`.
fn max_params_doc() -> String {
    let range = |b: &params::SlotBlock| format!("{}-{}", b.first, b.end - 1);
    let block = |owner: &str| BLOCKS.iter().find(|b| b.owner == owner).expect("a block");
    let (common, free) = (block("common"), block("free"));
    let kinds: Vec<String> = BLOCKS
        .iter()
        .filter(|b| Kind::from_name(b.owner).is_some())
        .map(|b| format!("{} {}", b.label, range(b)))
        .collect();
    format!(
        "Number of parameter slots in `OrientConfig.params`. Slots {} are {}; each kind has its \
         own block ({}); {} are {}.",
        range(common),
        common.label,
        kinds.join(", "),
        range(free),
        free.label
    )
}

/// The C constants of the parameter slots, rendered from the kinds' tables (each kind's
/// `settings!`, `params::COMMON` and `params::BLOCKS`): the text of `src/ffi/param_ids.rs`.
pub(crate) fn render_param_ids() -> String {
    let mut out = String::from(
        "//! Parameter slots for C. Generated from the parameter tables (each kind's `settings!`,\n\
         //! `params::COMMON` and the slot map `params::BLOCKS`) by the test\n\
         //! `param_ids_are_generated_from_the_tables` in `src/ffi/render.rs`; do not edit.\n\
         //! Regenerate: ORIENT_BLESS=1 cargo test -p orient --lib generated_from_the_tables\n\n",
    );
    doc_comment(&mut out, &max_params_doc());
    let _ = writeln!(out, "pub const ORIENT_MAX_PARAMS: usize = {};", params::MAX_PARAMS);
    let mut entry = |prefix: &str, who: &str, p: &ParamSpec| {
        let name = format!("ORIENT_PARAM_{prefix}{}", p.name.to_ascii_uppercase());
        let range = if p.zero_off {
            format!("0 (off) or {} to {}", p.min, p.max)
        } else {
            format!("{} to {}", p.min, p.max)
        };
        out.push('\n');
        doc_comment(&mut out, &format!("Parameter slot ({who}): {}", p.doc));
        let _ = writeln!(out, "///\n/// Unit {}; range {range}; default {}.", p.unit, p.default);
        let _ = writeln!(out, "pub const {name}: u32 = {};", p.id);
    };
    for p in COMMON.iter() {
        entry("", "every kind", p);
    }
    for kind in Kind::ALL {
        let prefix = format!("{}_", kind.name().to_ascii_uppercase());
        for p in kind.params().skip(COMMON.len()) {
            entry(&prefix, kind.name(), p);
        }
    }
    out
}

/// `x` with four significant digits (all the digits of an integer part up to 9999,
/// exponent form beyond it and below 10⁻³), without trailing zeros: 8.727e-4, 0.06981, 4.
fn short(x: f64) -> String {
    fn trim(digits: &str) -> &str {
        if digits.contains('.') {
            digits.trim_end_matches('0').trim_end_matches('.')
        } else {
            digits
        }
    }
    if x == 0.0 {
        return "0".to_string();
    }
    if x.abs() < 1e-3 || x.abs() >= 1e4 {
        let text = format!("{x:.3e}");
        let (mantissa, exponent) = text.split_once('e').expect("exponent form");
        return format!("{}e{exponent}", trim(mantissa));
    }
    let digits = (3 - x.abs().log10().floor() as i32).max(0) as usize;
    trim(&format!("{x:.digits$}")).to_string()
}

/// A value in its parameter's unit, with its degrees (for a unit in radians) and the
/// default's beside it: "8.727e-4 rad/s/sqrt(s) (0.05 deg/s/sqrt(s); its default 0.01
/// deg/s/sqrt(s))".
fn value_in_units(x: f64, default: f64, unit: &str) -> String {
    match unit.strip_prefix("rad") {
        Some(rest) => format!(
            "{} {unit} ({} deg{rest}; its default {} deg{rest})",
            short(x),
            short(x.to_degrees()),
            short(default.to_degrees())
        ),
        None => format!("{} {unit} (its default {} {unit})", short(x), short(default)),
    }
}

/// The doc of orient_config_for_joints, rendered from `joints::SENSOR_SETTINGS`: each
/// setting's C slot, value, default and reason.
fn for_joints_doc() -> String {
    use crate::joints::SENSOR_SETTINGS;
    let has_all = |k: &Kind| SENSOR_SETTINGS.iter().all(|s| k.param_by_name(s.name).is_some());
    let has_none = |k: &Kind| SENSOR_SETTINGS.iter().all(|s| k.param_by_name(s.name).is_none());
    let kinds: Vec<Kind> = Kind::ALL.into_iter().filter(has_all).collect();
    let one_kind = kinds.len() == 1 && Kind::ALL.iter().all(|k| has_all(k) || has_none(k));
    assert!(one_kind && !SENSOR_SETTINGS.is_empty(), "the sensor settings belong to one kind");
    let kind = kinds[0];
    let settings: Vec<String> = SENSOR_SETTINGS
        .iter()
        .map(|s| {
            let p = kind.param_by_name(s.name).expect("the kind's");
            // A parameter named in backticks reads as its C constant.
            let why: String = s
                .why
                .split('`')
                .enumerate()
                .map(|(i, piece)| match (i % 2, c_param(piece)) {
                    (1, Some(c)) => c,
                    (1, None) => format!("`{piece}`"),
                    _ => piece.to_string(),
                })
                .collect();
            let c = c_param(s.name).expect("a C name");
            format!("{c} at {}, {why}", value_in_units(s.value, p.default, p.unit))
        })
        .collect();
    let list = match settings.split_last() {
        Some((last, first)) if !first.is_empty() => format!("{}; and {last}", first.join("; ")),
        _ => settings.concat(),
    };
    format!(
        "Sets in `config` what a sensor's filter runs with under joints: for ORIENT_KIND_{}, {list}. \
         Other kinds have none of them and `config` is left as it was. Call it after \
         orient_config_default() for each sensor of a rig whose joints hold its heading \
         (docs/ACCURACY.md has the simulated gloves' figures); a sensor alone keeps the \
         defaults. NULL_POINTER for a NULL `config`; VERSION_MISMATCH for a `struct_size` \
         other than this header's; INVALID_ARGUMENT for an unknown kind, frame or init; \
         PARAM_OUT_OF_RANGE for a slot outside its parameter's range; a refused `config` is \
         left as it was.",
        kind.name().to_ascii_uppercase(),
    )
}

/// The text of `src/ffi/joint_settings.rs`: orient_config_for_joints with its doc.
pub(crate) fn render_joint_settings() -> String {
    let mut out = String::from(
        "//! orient_config_for_joints, whose doc is generated from `joints::SENSOR_SETTINGS` by the\n\
         //! test `joint_settings_are_generated_from_the_tables` in `src/ffi/render.rs`; do not\n\
         //! edit. Regenerate: ORIENT_BLESS=1 cargo test -p orient --lib generated_from_the_tables\n\n\
         use super::*;\n\n",
    );
    doc_comment(&mut out, &for_joints_doc());
    out.push_str(
        "#[no_mangle]\n\
         pub unsafe extern \"C\" fn orient_config_for_joints(config: *mut OrientConfig) \
         -> OrientStatus {\n    joints::config_for_joints(config)\n\
         }\n",
    );
    out
}

/// Fails unless the committed `src/ffi/{file}` is `want`; writes it with ORIENT_BLESS=1.
fn check_generated(file: &str, want: &str) {
    let path = format!("{}/src/ffi/{file}", env!("CARGO_MANIFEST_DIR"));
    if std::env::var_os("ORIENT_BLESS").is_some() {
        std::fs::write(&path, want).unwrap();
    }
    let have = std::fs::read_to_string(&path).unwrap();
    assert!(
        have == want,
        "src/ffi/{file} is stale: ORIENT_BLESS=1 cargo test -p orient --lib generated_from_the_tables"
    );
}

#[test]
#[cfg_attr(miri, ignore = "reads a file")]
fn param_ids_are_generated_from_the_tables() {
    check_generated("param_ids.rs", &render_param_ids());
}

#[test]
#[cfg_attr(miri, ignore = "reads a file")]
fn bits_are_generated_from_the_tables() {
    check_generated("bits.rs", &render_bits());
}

#[test]
#[cfg_attr(miri, ignore = "reads a file")]
fn joint_settings_are_generated_from_the_tables() {
    check_generated("joint_settings.rs", &render_joint_settings());
}

#[test]
fn values_are_written_short() {
    assert_eq!(short(8.726_646_259_971_648e-4), "8.727e-4");
    assert_eq!(short(0.069_813_170_079_773_18), "0.06981");
    assert_eq!(short(4.000_000_000_001), "4");
    assert_eq!(short(0.05), "0.05");
    assert_eq!(short(1234.5), "1234");
    assert_eq!(short(0.0), "0");
    assert_eq!(short(-0.0), "0");
    assert_eq!(short(5e-4), "5e-4");
    assert_eq!(short(-5.25e-4), "-5.25e-4");
    assert_eq!(short(12_345.6), "1.235e4");
    assert_eq!(short(-0.5), "-0.5");
    assert_eq!(
        value_in_units(0.069_813_170_079_773_18, 0.0349, "rad/s"),
        "0.06981 rad/s (4 deg/s; its default 2 deg/s)"
    );
    assert_eq!(value_in_units(0.5, 0.25, "m/s^2"), "0.5 m/s^2 (its default 0.25 m/s^2)");
}

#[test]
fn the_slot_map_covers_every_slot_once_and_holds_every_parameter() {
    // In slot order, without gaps or overlaps, from 0 to MAX_PARAMS.
    let mut next = 0;
    for b in BLOCKS {
        assert!(b.first == next && b.end > b.first, "{b:?} does not start at slot {next}");
        next = b.end;
    }
    assert_eq!(next as usize, params::MAX_PARAMS);
    // The common slots, every kind's block in Kind::ALL order, the free slots.
    let owners: Vec<&str> = BLOCKS.iter().map(|b| b.owner).collect();
    let kinds: Vec<&str> = Kind::ALL.iter().map(|k| k.name()).collect();
    assert_eq!(owners, [&["common"][..], &kinds, &["free"]].concat());
    let block = |owner: &str| BLOCKS.iter().find(|b| b.owner == owner).unwrap();
    let within = |owner: &str, p: &ParamSpec| {
        let b = block(owner);
        assert!((b.first..b.end).contains(&p.id), "{owner}: {} in slot {}, outside {b:?}", p.name, p.id);
    };
    for p in COMMON.iter() {
        within("common", p);
    }
    for kind in Kind::ALL {
        for p in kind.params().skip(COMMON.len()) {
            within(kind.name(), p);
        }
    }
}

#[test]
fn a_bit_doc_reads_as_c() {
    let table = [
        BitSpec { name: "ONE", value: 1, doc: " The first; see [`TWO`].\n" },
        BitSpec { name: "TWO", value: 2, doc: " With `gap_dt`, `init_duration`,\n `kp` and `other`.\n" },
    ];
    let c = |i: usize| c_doc(&table[i], &table, "ORIENT_X_", "`what`");
    assert_eq!(c(0), "`what`: the first; see ORIENT_X_TWO.");
    assert_eq!(
        c(1),
        "`what`: with ORIENT_PARAM_GAP_DT, ORIENT_PARAM_*_INIT_DURATION, ORIENT_PARAM_*_KP and `other`."
    );
    let one_kind = BitSpec { name: "X", value: 4, doc: " `beta`? No: `rest_rate_std`.\n" };
    assert_eq!(c_doc(&one_kind, &table, "ORIENT_X_", "w"), "w: `beta`? No: ORIENT_PARAM_EKF_REST_RATE_STD.");
}
