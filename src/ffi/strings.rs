//! NUL-terminated copies of the parameter tables' strings, built at compile time from
//! the tables themselves (`params::COMMON` and each kind's `PARAMS`). They live in the
//! library's read-only data: loading and unloading the library allocates nothing for
//! them, so nothing is left behind by a dlopen/dlclose cycle.

use crate::filters::params::{ParamSpec, COMMON, MAX_PARAMS};
use crate::filters::{complementary, ekf, gmvdk, madgwick, mahony, robust};
use core::ffi::c_char;

/// Every parameter table: the common one and each kind's own. A kind whose table is
/// missing here is caught by the test below (and reported as a bug at run time).
const TABLES: [&[ParamSpec]; 7] = [
    &COMMON,
    madgwick::PARAMS,
    mahony::PARAMS,
    complementary::PARAMS,
    ekf::PARAMS,
    gmvdk::PARAMS,
    robust::PARAMS,
];

/// A parameter's strings in [`ParamText`] order.
const fn fields(p: &ParamSpec) -> [&'static str; 3] {
    [p.name, p.unit, p.doc]
}

/// Bytes of every string of every table, each with its NUL.
const fn text_len() -> usize {
    let (mut n, mut t) = (0, 0);
    while t < TABLES.len() {
        let mut i = 0;
        while i < TABLES[t].len() {
            let f = fields(&TABLES[t][i]);
            n += f[0].len() + f[1].len() + f[2].len() + 3;
            i += 1;
        }
        t += 1;
    }
    n
}

const LEN: usize = text_len();
/// `at` entry of a slot no parameter uses.
const NONE: usize = usize::MAX;

struct Table {
    /// The strings, one after the other, each NUL-terminated.
    text: [u8; LEN],
    /// Per parameter slot: where its name, unit and doc start in `text`.
    at: [[usize; 3]; MAX_PARAMS],
}

const fn build() -> Table {
    let mut text = [0u8; LEN];
    let mut at = [[NONE; 3]; MAX_PARAMS];
    let (mut end, mut t) = (0, 0);
    while t < TABLES.len() {
        let mut i = 0;
        while i < TABLES[t].len() {
            let p = &TABLES[t][i];
            let id = p.id as usize;
            assert!(id < MAX_PARAMS && at[id][0] == NONE, "two parameters share a slot");
            let f = fields(p);
            let mut k = 0;
            while k < 3 {
                at[id][k] = end;
                let bytes = f[k].as_bytes();
                let mut j = 0;
                while j < bytes.len() {
                    assert!(bytes[j] != 0, "a parameter string holds a NUL");
                    text[end] = bytes[j];
                    end += 1;
                    j += 1;
                }
                end += 1; // the NUL: `text` starts zeroed
                k += 1;
            }
            i += 1;
        }
        t += 1;
    }
    Table { text, at }
}

static TABLE: Table = build();

/// A parameter's static, NUL-terminated strings.
pub(super) struct ParamText {
    pub name: *const c_char,
    pub unit: *const c_char,
    pub doc: *const c_char,
}

/// The static C strings of the parameter in slot `id`; `None` for a slot no table uses.
pub(super) fn param_text(id: u32) -> Option<ParamText> {
    let at = TABLE.at.get(id as usize).filter(|at| at[0] != NONE)?;
    let ptr = |k: usize| TABLE.text[at[k]..].as_ptr() as *const c_char;
    Some(ParamText { name: ptr(0), unit: ptr(1), doc: ptr(2) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filters::Kind;
    use core::ffi::CStr;

    #[test]
    fn every_parameter_of_every_kind_has_its_strings() {
        let text = |p: *const c_char| unsafe { CStr::from_ptr(p) }.to_str().unwrap();
        let mut seen = 0;
        for kind in Kind::ALL {
            for p in kind.params() {
                let t = param_text(p.id).unwrap_or_else(|| panic!("{kind:?}: slot {} has no strings", p.id));
                assert_eq!((text(t.name), text(t.unit), text(t.doc)), (p.name, p.unit, p.doc));
                seen += 1;
            }
        }
        assert!(seen > 50);
        // Nothing but the kinds' parameters is in the table.
        let used = (0..MAX_PARAMS as u32).filter(|id| param_text(*id).is_some()).count();
        let ids: std::collections::BTreeSet<u32> =
            Kind::ALL.iter().flat_map(|k| k.params().map(|p| p.id)).collect();
        assert_eq!(used, ids.len());
        assert!(param_text(MAX_PARAMS as u32).is_none());
    }
}
