//! A count of shadow rays shared by a render's threads, exact, without a locked
//! instruction per ray.
//!
//! Every thread that counts leases a small id of its own ([`SLOTS`] of them, taken from
//! a free list when the thread first counts and given back when it exits), and every
//! counter has one slot per id, each on its own cache line. A thread is then the only
//! writer of its slot and adds with a plain load and store. An atomic add (`lock xadd`)
//! on every shadow ray also waits for the core's pending stores to drain: 2–3 % of the
//! CPU time of `cbox_diffuse.xml` and 1–2 % of the README's render (BENCHMARKS.md,
//! session 34). Threads beyond [`SLOTS`] alive at once share one more slot, with atomic
//! adds.
//!
//! Exactness: a slot's owner is its only writer while it holds the id. A thread that
//! takes an id another thread gave back locks the free list after that thread unlocked
//! it, so the earlier thread's last store happens before the new owner's first load.

use std::cell::Cell;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Ids a thread may own; one more slot is shared by any threads beyond.
const SLOTS: usize = 64;

/// A count of shadow rays (see the module doc). Cloning copies the count.
#[derive(Debug)]
pub struct ShadowRays(Box<[Slot; SLOTS + 1]>);

/// One id's count, alone on its cache line.
#[derive(Debug, Default)]
#[repr(align(128))]
struct Slot(AtomicU64);

/// The ids no live thread holds: the lowest never handed out, and those given back.
static FREE: Mutex<(usize, Vec<usize>)> = Mutex::new((0, Vec::new()));

/// A thread's id, given back when the thread exits; [`SLOTS`] for the shared slot.
struct Lease(usize);

impl Lease {
    fn take() -> Lease {
        let mut free = FREE.lock().unwrap_or_else(|e| e.into_inner());
        let (next, given_back) = &mut *free;
        Lease(match given_back.pop() {
            Some(id) => id,
            None if *next < SLOTS => {
                *next += 1;
                *next - 1
            }
            None => SLOTS,
        })
    }
}

impl Drop for Lease {
    fn drop(&mut self) {
        // Anything this thread still counts goes to the shared slot.
        let _ = ID.try_with(|id| id.set(Some(SLOTS)));
        if self.0 < SLOTS {
            FREE.lock()
                .unwrap_or_else(|e| e.into_inner())
                .1
                .push(self.0);
        }
    }
}

thread_local! {
    static LEASE: Lease = Lease::take();
    /// The lease's id, read without the lazy initialisation check of `LEASE`.
    static ID: Cell<Option<usize>> = const { Cell::new(None) };
}

/// The calling thread's id, leased on first use; the shared slot's while the thread's
/// local storage is being torn down.
#[inline]
fn id() -> usize {
    ID.try_with(|id| match id.get() {
        Some(i) => i,
        None => {
            let i = LEASE.try_with(|l| l.0).unwrap_or(SLOTS);
            id.set(Some(i));
            i
        }
    })
    .unwrap_or(SLOTS)
}

impl Default for ShadowRays {
    fn default() -> Self {
        ShadowRays(Box::new(std::array::from_fn(|_| Slot::default())))
    }
}

impl ShadowRays {
    /// Counts one shadow ray.
    #[inline]
    pub(super) fn add(&self) {
        let i = id();
        let slot = &self.0[i].0;
        if i < SLOTS {
            // This thread is the slot's only writer.
            slot.store(slot.load(Ordering::Relaxed) + 1, Ordering::Relaxed);
        } else {
            slot.fetch_add(1, Ordering::Relaxed);
        }
    }

    /// The count so far.
    pub fn get(&self) -> u64 {
        self.0.iter().map(|s| s.0.load(Ordering::Relaxed)).sum()
    }
}

impl Clone for ShadowRays {
    fn clone(&self) -> Self {
        let copy = ShadowRays::default();
        copy.0[SLOTS].0.store(self.get(), Ordering::Relaxed);
        copy
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Barrier;

    /// The two tests one at a time: the first holds more ids than there are.
    static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

    /// More threads alive at once than there are slots, each counting many rays while
    /// the others do: the count is exact (a shared slot written by plain stores would
    /// lose some), and a clone carries it.
    #[test]
    fn more_threads_than_slots_count_exactly() {
        let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
        let rays = ShadowRays::default();
        let threads = SLOTS + 36;
        let barrier = Barrier::new(threads);
        std::thread::scope(|s| {
            for _ in 0..threads {
                s.spawn(|| {
                    barrier.wait();
                    for _ in 0..20_000 {
                        rays.add();
                    }
                    // Keep every lease until all have counted.
                    barrier.wait();
                });
            }
        });
        assert_eq!(rays.get(), threads as u64 * 20_000);
        assert_eq!(rays.clone().get(), rays.get());
    }

    /// Threads that come and go one after another reuse the ids the earlier ones gave
    /// back (so they keep the unlocked add), and the count stays exact. Each thread is
    /// joined itself: the scope's own join may return before the thread's local storage
    /// (and its lease) is dropped.
    #[test]
    fn ids_are_given_back() {
        let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
        let rays = ShadowRays::default();
        let mut shared = 0;
        for _ in 0..3 * SLOTS {
            let own = std::thread::scope(|s| {
                s.spawn(|| {
                    rays.add();
                    rays.add();
                    id()
                })
                .join()
                .expect("no panic")
            });
            shared += (own == SLOTS) as u32;
        }
        assert_eq!(rays.get(), 6 * SLOTS as u64);
        // Without ids given back, all but the first few of these threads would share the
        // slot. Other tests' threads (the rayon pool's, the test harness's: about two per
        // core) hold some ids meanwhile; on a machine of many cores they may hold most.
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        if cores < SLOTS / 8 {
            assert_eq!(shared, 0, "{cores} cores");
        }
    }
}
