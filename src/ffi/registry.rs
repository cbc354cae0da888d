//! The registry of live handles: the address of every OrientFilter that
//! orient_filter_new returned and orient_filter_free has not released.
//!
//! A handle check looks the pointer's address up here and reads nothing at that address,
//! so a freed handle, a byte copy of a live one and a block forged to look like one are
//! refused without their memory being touched. The table is a fixed array of atomic
//! slots in the library's static data: nothing is allocated (creating a handle included),
//! so nothing is left behind when the library is unloaded. Lookups take no lock and
//! write nothing, so threads that update different handles do not contend; insertions
//! and removals (orient_filter_new and orient_filter_free only) hold one mutex.
//!
//! Open addressing with linear probing. A removed entry becomes a tombstone ([`GONE`])
//! that lookups probe past and insertions reuse, because moving entries would let a
//! concurrent lookup miss a live one; a run of tombstones that ends at an empty slot
//! is emptied again (no probe path continues through it).
//!
//! What an address cannot tell: once the allocator hands a freed handle's address to
//! a new filter, that address is the new filter's handle.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard};

const BITS: u32 = 15;
const SLOTS: usize = 1 << BITS;
/// Most handles live at once. The table stays at most three quarters full, so that a
/// lookup finds a live handle in a probe or two.
pub(super) const CAPACITY: usize = SLOTS / 4 * 3;
const EMPTY: usize = 0;
/// A removed entry. Handles are aligned, so no handle's address is 1.
const GONE: usize = 1;

pub(super) struct Registry {
    slots: [AtomicUsize; SLOTS],
    /// Held while the table changes; the number of live handles.
    live: Mutex<usize>,
}

/// The handles of this process.
pub(super) static HANDLES: Registry = Registry::new();

/// The slot where the probe for `addr` starts: Fibonacci hashing of the address
/// without its alignment bits (the product's top `BITS` bits).
#[inline(always)]
fn home(addr: usize) -> usize {
    ((addr as u64 >> 3).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - BITS)) as usize
}

#[inline(always)]
fn next(i: usize) -> usize {
    (i + 1) & (SLOTS - 1)
}

impl Registry {
    pub(super) const fn new() -> Registry {
        #[allow(clippy::declare_interior_mutable_const)] // a template: each slot is its own
        const VACANT: AtomicUsize = AtomicUsize::new(EMPTY);
        Registry { slots: [VACANT; SLOTS], live: Mutex::new(0) }
    }

    fn lock(&self) -> MutexGuard<'_, usize> {
        // Nothing panics while the lock is held; a poisoned lock still holds a valid count.
        self.live.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Whether `addr` is a live handle. Reads only the table.
    #[inline(always)]
    pub(super) fn contains(&self, addr: usize) -> bool {
        let mut i = home(addr);
        // A live handle's probe path has no empty slot: the first empty slot ends the
        // search. The bound covers a table without any empty slot.
        for _ in 0..SLOTS {
            match self.slots[i].load(Ordering::Acquire) {
                v if v == addr && addr > GONE => return true,
                EMPTY => return false,
                _ => i = next(i),
            }
        }
        false
    }

    /// Records `addr` as live; false (nothing recorded) when [`CAPACITY`] handles are
    /// live already. `addr` is not live (the allocator just handed it out).
    pub(super) fn insert(&self, addr: usize) -> bool {
        let mut live = self.lock();
        if *live >= CAPACITY || addr <= GONE {
            return false;
        }
        let mut i = home(addr);
        // Fewer than CAPACITY < SLOTS entries: a free slot exists.
        while !matches!(self.slots[i].load(Ordering::Relaxed), EMPTY | GONE) {
            i = next(i);
        }
        self.slots[i].store(addr, Ordering::Release);
        *live += 1;
        true
    }

    /// Removes `addr`; false when it was not live (so of two frees of one handle, even
    /// from two threads, exactly one succeeds).
    pub(super) fn remove(&self, addr: usize) -> bool {
        let mut live = self.lock();
        if addr <= GONE {
            return false;
        }
        let mut i = home(addr);
        for _ in 0..SLOTS {
            match self.slots[i].load(Ordering::Relaxed) {
                v if v == addr => {
                    self.slots[i].store(GONE, Ordering::Release);
                    *live -= 1;
                    if self.slots[next(i)].load(Ordering::Relaxed) == EMPTY {
                        let mut k = i;
                        while self.slots[k].load(Ordering::Relaxed) == GONE {
                            self.slots[k].store(EMPTY, Ordering::Release);
                            k = (k + SLOTS - 1) & (SLOTS - 1);
                        }
                    }
                    return true;
                }
                EMPTY => return false,
                _ => i = next(i),
            }
        }
        false
    }

    #[cfg(test)]
    fn used_slots(&self) -> usize {
        self.slots.iter().filter(|s| s.load(Ordering::Relaxed) != EMPTY).count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    /// Aligned addresses that all start their probe at slot `h` (probing, tombstones
    /// and their clean-up are exercised on one run).
    fn colliding(h: usize, n: usize) -> Vec<usize> {
        (1..).map(|k| k * 16).filter(|a| home(*a) == h).take(n).collect()
    }

    #[test]
    fn colliding_handles_are_found_until_removed_and_tombstones_are_cleared() {
        let r = Box::new(Registry::new());
        let a = colliding(SLOTS - 2, 5); // the run wraps around the end of the table
        for x in &a {
            assert!(r.insert(*x));
        }
        assert!(a.iter().all(|x| r.contains(*x)));
        assert!(!r.contains(a[4] + 8) && !r.contains(0) && !r.contains(GONE));
        // Removing from the middle leaves a tombstone that lookups probe past.
        assert!(r.remove(a[1]));
        assert!(!r.remove(a[1]), "a second removal succeeded");
        assert!(!r.contains(a[1]));
        assert!([0, 2, 3, 4].iter().all(|k| r.contains(a[*k])));
        assert_eq!(r.used_slots(), 5);
        // The last of the run goes: the tombstones before it go with it.
        assert!(r.remove(a[4]) && r.remove(a[3]) && r.remove(a[2]));
        assert_eq!(r.used_slots(), 1);
        assert!(r.contains(a[0]));
        // A new entry reuses the first free slot of its path.
        assert!(r.insert(a[2]));
        assert!(r.contains(a[2]) && r.contains(a[0]));
        assert_eq!(r.used_slots(), 2);
    }

    #[test]
    #[cfg_attr(miri, ignore = "safe code only, and 200,000 steps")]
    fn random_churn_matches_a_set_and_the_capacity_holds() {
        let r = Box::new(Registry::new());
        let mut model = BTreeSet::new();
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut rand = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        // Addresses from a small range, so that the same ones come back.
        for step in 0..200_000 {
            let addr = 16 * (1 + (rand() % 30_000) as usize);
            if model.contains(&addr) {
                assert!(r.remove(addr), "step {step}");
                model.remove(&addr);
            } else if rand() % 3 != 0 {
                assert_eq!(r.insert(addr), model.len() < CAPACITY, "step {step}");
                if model.len() < CAPACITY {
                    model.insert(addr);
                }
            }
            if step % 1000 == 0 {
                let probe = 16 * (1 + (rand() % 30_000) as usize);
                assert_eq!(r.contains(probe), model.contains(&probe), "step {step}");
            }
        }
        assert!(model.iter().all(|a| r.contains(*a)));
        // Fill to the capacity: one more is refused, and one free makes room again.
        let mut a = 16 * 40_000;
        while model.len() < CAPACITY {
            assert!(r.insert(a));
            model.insert(a);
            a += 16;
        }
        assert!(!r.insert(a));
        let first = *model.iter().next().unwrap();
        assert!(r.remove(first));
        assert!(r.insert(a) && r.contains(a));
    }
}
