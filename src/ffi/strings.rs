//! NUL-terminated copies of the parameter tables' strings, built at compile time from
//! the tables themselves (`params::COMMON`, each kind's `PARAMS` and the joints'
//! `JOINT_PARAMS`). They live in the
//! library's read-only data: loading and unloading the library allocates nothing for
//! them, so nothing is left behind by a dlopen/dlclose cycle.

use crate::filters::params::{ParamSpec, COMMON, MAX_PARAMS};
use crate::filters::{complementary, ekf, gmvdk, madgwick, mahony, robust};
use crate::joints::JOINT_PARAMS;
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
const fn text_len(tables: &[&[ParamSpec]]) -> usize {
    let (mut n, mut t) = (0, 0);
    while t < tables.len() {
        let mut i = 0;
        while i < tables[t].len() {
            let f = fields(&tables[t][i]);
            n += f[0].len() + f[1].len() + f[2].len() + 3;
            i += 1;
        }
        t += 1;
    }
    n
}

/// `at` entry of a slot no parameter uses.
const NONE: usize = usize::MAX;

/// `L` bytes of strings for `S` slots.
struct Table<const L: usize, const S: usize> {
    /// The strings, one after the other, each NUL-terminated.
    text: [u8; L],
    /// Per parameter slot: where its name, unit and doc start in `text`.
    at: [[usize; 3]; S],
}

const fn build<const L: usize, const S: usize>(tables: &[&[ParamSpec]]) -> Table<L, S> {
    let mut text = [0u8; L];
    let mut at = [[NONE; 3]; S];
    let (mut end, mut t) = (0, 0);
    while t < tables.len() {
        let mut i = 0;
        while i < tables[t].len() {
            let p = &tables[t][i];
            let id = p.id as usize;
            assert!(id < S && at[id][0] == NONE, "two parameters share a slot");
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

impl<const L: usize, const S: usize> Table<L, S> {
    fn get(&'static self, id: u32) -> Option<ParamText> {
        let at = self.at.get(id as usize).filter(|at| at[0] != NONE)?;
        let ptr = |k: usize| self.text[at[k]..].as_ptr() as *const c_char;
        Some(ParamText { name: ptr(0), unit: ptr(1), doc: ptr(2) })
    }
}

const LEN: usize = text_len(&TABLES);
static TABLE: Table<LEN, MAX_PARAMS> = build(&TABLES);

/// The joints' tuning ([`JOINT_PARAMS`]), slots by index.
const JOINT_TABLES: [&[ParamSpec]; 1] = [&JOINT_PARAMS];
const JOINT_LEN: usize = text_len(&JOINT_TABLES);
static JOINT_TABLE: Table<JOINT_LEN, { JOINT_PARAMS.len() }> = build(&JOINT_TABLES);

/// A parameter's static, NUL-terminated strings.
pub(super) struct ParamText {
    pub name: *const c_char,
    pub unit: *const c_char,
    pub doc: *const c_char,
}

/// The static C strings of the parameter in slot `id`; `None` for a slot no table uses.
pub(super) fn param_text(id: u32) -> Option<ParamText> {
    TABLE.get(id)
}

/// The static C strings of joint parameter `index` ([`JOINT_PARAMS`]).
pub(super) fn joint_param_text(index: u32) -> Option<ParamText> {
    JOINT_TABLE.get(index)
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

    #[test]
    fn every_joint_parameter_has_its_strings() {
        let text = |p: *const c_char| unsafe { CStr::from_ptr(p) }.to_str().unwrap();
        for (k, p) in JOINT_PARAMS.iter().enumerate() {
            let t = joint_param_text(k as u32).unwrap();
            assert_eq!((text(t.name), text(t.unit), text(t.doc)), (p.name, p.unit, p.doc));
        }
        assert!(joint_param_text(JOINT_PARAMS.len() as u32).is_none());
    }
}
