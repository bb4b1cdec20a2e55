//! Memory for large syntax trees: a global allocator for hosts that parse large
//! files ([`LargePages`]), and faulting a tree's pages in on a second thread while it
//! is built ([`prefault_while`]).
//!
//! A parsed program is a handful of large vectors (items, blocks, the text), written
//! once from front to back. With the default allocator each of their 4 KiB pages
//! costs the kernel a page fault when it is first written; on the real-time kernel of
//! the virtual machine where BENCHMARKS.md was measured a fault costs several
//! microseconds, and for a 500 000-line program the faults took longer than the parse
//! itself (BENCHMARKS.md, session 6).
//! `LargePages` maps every allocation of at least [`LARGE`] bytes itself, aligned to
//! 2 MiB and marked for transparent huge pages, so the kernel backs it with 2 MiB
//! pages where it can: one fault per 2 MiB instead of 512. Everything smaller goes to
//! the system allocator.
//!
//! The cost is memory: a huge page is resident as soon as one byte of it is written,
//! so each large allocation may hold up to 2 MiB more than the 4 KiB pages would.
//! Where the kernel has transparent huge pages switched off, or cannot find a free
//! 2 MiB page, the mapping simply gets 4 KiB pages. On other systems than Linux the
//! type is the system allocator.
//!
//! A host installs it with
//! `#[global_allocator] static ALLOC: analyzer::memory::LargePages = analyzer::memory::LargePages;`.
//!
//! A freed large block is kept (up to 512 MiB in eight blocks) and handed out again
//! by the next large allocation, resized to fit: its pages are already faulted in,
//! so a host that parses file after file pays the faults once. Every large
//! allocation takes a kept block first, so keeping them never raises a process's
//! peak memory above what it held before the free.
//!
//! It suits work that parses large files (the command line, benchmarks). A
//! long-running host whose large blocks vary in size and number (the language
//! server) does better with the system allocator, which reuses freed memory at a
//! finer grain: such a host calls [`LargePages::disable`] first thing.

#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicU8, AtomicUsize, Ordering};

/// 0: large blocks are mapped (the default); 1: a large block has been mapped, so it
/// can no longer be switched off; 2: switched off, everything goes to `System`.
static STATE: AtomicU8 = AtomicU8::new(0);
const ON: u8 = 0;
const USED: u8 = 1;
const OFF: u8 = 2;

impl LargePages {
    /// Sends every allocation to the system allocator from now on. Only possible
    /// before the first large block is mapped (a block must be freed the way it was
    /// made); returns whether it took effect.
    pub fn disable() -> bool {
        match STATE.compare_exchange(ON, OFF, Ordering::SeqCst, Ordering::SeqCst) {
            Ok(_) => true,
            Err(state) => state == OFF,
        }
    }

    fn enabled() -> bool {
        STATE.load(Ordering::Relaxed) != OFF
    }
}

/// Allocations of at least this many bytes are mapped with huge pages.
pub const LARGE: usize = 4 << 20;

/// The allocator (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
pub struct LargePages;

#[cfg(target_os = "linux")]
mod large {
    /// The huge page size of x86-64 and of most aarch64 kernels; on others the
    /// alignment is merely generous.
    const HUGE: usize = 2 << 20;

    pub fn round(len: usize) -> Option<usize> {
        len.checked_add(HUGE - 1).map(|l| l & !(HUGE - 1))
    }

    /// Maps `len` (a multiple of [`HUGE`]) zeroed bytes at a 2 MiB boundary, or
    /// returns null.
    ///
    /// # Safety
    /// Plain system calls; the caller owns the returned mapping.
    pub unsafe fn map(len: usize) -> *mut u8 {
        let Some(span) = len.checked_add(HUGE) else {
            return std::ptr::null_mut();
        };
        // SAFETY: an anonymous private mapping at an address the kernel chooses.
        let raw = unsafe {
            libc::mmap(
                std::ptr::null_mut(),
                span,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS | libc::MAP_NORESERVE,
                -1,
                0,
            )
        };
        if raw == libc::MAP_FAILED {
            return std::ptr::null_mut();
        }
        // Over-map by one huge page and give back the unaligned head and tail, so
        // the kernel can back the whole range with huge pages.
        let addr = raw as usize;
        let start = (addr + HUGE - 1) & !(HUGE - 1);
        let head = start - addr;
        let tail = span - head - len;
        // SAFETY: both ranges lie inside the mapping just made and are not used.
        unsafe {
            if head > 0 {
                libc::munmap(raw, head);
            }
            if tail > 0 {
                libc::munmap((start + len) as *mut libc::c_void, tail);
            }
            // Advice only: a kernel without transparent huge pages ignores it.
            libc::madvise(start as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
        }
        start as *mut u8
    }

    /// # Safety
    /// `ptr`/`len` must be a mapping made by [`map`] with this (rounded) length.
    pub unsafe fn unmap(ptr: *mut u8, len: usize) {
        // SAFETY: the caller passes a whole mapping of ours.
        unsafe {
            libc::munmap(ptr as *mut libc::c_void, len);
        }
    }

    /// Grows or shrinks a mapping of ours, moving it if needed (the kernel moves the
    /// page tables, not the bytes); null when it cannot.
    ///
    /// # Safety
    /// `ptr`/`old` must be a mapping made by [`map`]; `new` is rounded.
    pub unsafe fn remap(ptr: *mut u8, old: usize, new: usize) -> *mut u8 {
        // SAFETY: the caller passes a whole mapping of ours.
        let p = unsafe { libc::mremap(ptr as *mut libc::c_void, old, new, libc::MREMAP_MAYMOVE) };
        if p == libc::MAP_FAILED {
            return std::ptr::null_mut();
        }
        // SAFETY: advice on the mapping just returned.
        unsafe {
            libc::madvise(p, new, libc::MADV_HUGEPAGE);
        }
        p as *mut u8
    }
}

/// Freed large blocks kept for the next large allocation, up to [`RETAIN`] bytes
/// in [`SLOTS`] blocks.
///
/// A freed mapping's pages stay faulted in, so a block made from it costs no page
/// faults or zeroing: a host that parses file after file (the command line on a
/// directory, a benchmark) pays those once. Every large allocation takes one back
/// if there is one (resized to fit), so keeping them never raises the peak memory
/// of a process above what it held before the free.
#[cfg(target_os = "linux")]
mod retained {
    use std::sync::Mutex;

    pub const SLOTS: usize = 8;
    pub const RETAIN: usize = 512 << 20;

    /// `(address, rounded length)`; length 0 marks a free slot. A `Mutex` from
    /// `std` never allocates, so the allocator may use it.
    static KEPT: Mutex<[(usize, usize); SLOTS]> = Mutex::new([(0, 0); SLOTS]);

    /// Keeps a freed mapping if there is room; `false` when the caller must unmap it.
    pub fn keep(addr: usize, len: usize) -> bool {
        let Ok(mut kept) = KEPT.lock() else {
            return false;
        };
        let total: usize = kept.iter().map(|k| k.1).sum();
        if total.saturating_add(len) > RETAIN {
            return false;
        }
        match kept.iter_mut().find(|k| k.1 == 0) {
            Some(slot) => {
                *slot = (addr, len);
                true
            }
            None => false,
        }
    }

    /// Takes the kept mapping that best fits `len` bytes: the smallest at least as
    /// long, otherwise the longest. Returns `(address, its length)`.
    pub fn take(len: usize) -> Option<(usize, usize)> {
        let mut kept = KEPT.lock().ok()?;
        let fits = kept
            .iter()
            .enumerate()
            .filter(|(_, k)| k.1 >= len)
            .min_by_key(|(_, k)| k.1)
            .map(|(i, _)| i);
        let i = fits.or_else(|| {
            kept.iter()
                .enumerate()
                .filter(|(_, k)| k.1 > 0)
                .max_by_key(|(_, k)| k.1)
                .map(|(i, _)| i)
        })?;
        let taken = kept[i];
        kept[i] = (0, 0);
        Some(taken)
    }
}

/// Keeps the switch on from now on, because a large block is about to be mapped
/// (it must be unmapped when freed); `false` if it was switched off meanwhile. The
/// claim comes before the mapping, so a `disable` racing with it fails.
#[cfg(target_os = "linux")]
fn claim() -> bool {
    STATE.load(Ordering::Relaxed) == USED
        || matches!(
            STATE.compare_exchange(ON, USED, Ordering::SeqCst, Ordering::SeqCst),
            Ok(_) | Err(USED)
        )
}

#[cfg(target_os = "linux")]
fn is_large(layout: &Layout) -> bool {
    // Larger alignments than a page are left to the system allocator, which honours
    // them; a mapping only guarantees page alignment after `mremap`.
    layout.size() >= LARGE && layout.align() <= 4096 && LargePages::enabled()
}

#[cfg(target_os = "linux")]
// SAFETY: large blocks are private anonymous mappings of at least the requested
// size, page aligned (which covers the alignments `is_large` admits), zeroed, and
// released with the same rounded length; everything else is `System`'s.
unsafe impl GlobalAlloc for LargePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !is_large(&layout) {
            // SAFETY: forwarded with the caller's guarantees.
            return unsafe { System.alloc(layout) };
        }
        if !claim() {
            // SAFETY: switched off meanwhile: a `System` block like any other.
            return unsafe { System.alloc(layout) };
        }
        let Some(len) = large::round(layout.size()) else {
            return std::ptr::null_mut();
        };
        if let Some((addr, kept)) = retained::take(len) {
            if kept == len {
                return addr as *mut u8;
            }
            // SAFETY: a whole mapping of ours, no longer in use, resized whole.
            let p = unsafe { large::remap(addr as *mut u8, kept, len) };
            if !p.is_null() {
                return p;
            }
            // SAFETY: as above; it could not be resized, so it is released.
            unsafe { large::unmap(addr as *mut u8, kept) };
        }
        // SAFETY: a fresh mapping.
        unsafe { large::map(len) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !is_large(&layout) {
            // SAFETY: forwarded with the caller's guarantees.
            return unsafe { System.alloc_zeroed(layout) };
        }
        // A kept mapping holds old bytes: zeroed blocks are always fresh mappings,
        // which the kernel zeroes.
        if !claim() {
            // SAFETY: switched off meanwhile: a `System` block like any other.
            return unsafe { System.alloc_zeroed(layout) };
        }
        match large::round(layout.size()) {
            // SAFETY: a fresh mapping.
            Some(len) => unsafe { large::map(len) },
            None => std::ptr::null_mut(),
        }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if !is_large(&layout) {
            // SAFETY: the block came from `System` with this layout.
            return unsafe { System.dealloc(ptr, layout) };
        }
        if let Some(len) = large::round(layout.size()) {
            if !retained::keep(ptr as usize, len) {
                // SAFETY: the block is one of our mappings of this rounded length.
                unsafe { large::unmap(ptr, len) }
            }
        }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let Ok(new_layout) = Layout::from_size_align(new_size, layout.align()) else {
            return std::ptr::null_mut();
        };
        match (is_large(&layout), is_large(&new_layout)) {
            // SAFETY: a `System` block resized by `System`.
            (false, false) => unsafe { System.realloc(ptr, layout, new_size) },
            (true, true) => match (large::round(layout.size()), large::round(new_size)) {
                (Some(old), Some(new)) if old == new => ptr,
                // SAFETY: one of our mappings, resized whole.
                (Some(old), Some(new)) => unsafe { large::remap(ptr, old, new) },
                _ => std::ptr::null_mut(),
            },
            _ => {
                // Crossing the threshold: a new block of the other kind and a copy.
                // SAFETY: `new_layout` is valid; the copy stays within both blocks;
                // the old block is released with its own layout.
                unsafe {
                    let new = self.alloc(new_layout);
                    if !new.is_null() {
                        std::ptr::copy_nonoverlapping(ptr, new, layout.size().min(new_size));
                        self.dealloc(ptr, layout);
                    }
                    new
                }
            }
        }
    }
}

#[cfg(not(target_os = "linux"))]
// SAFETY: every call is forwarded to `System` unchanged.
unsafe impl GlobalAlloc for LargePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// Faults in the pages of large buffers on a second thread while the calling thread
/// fills them from the front: the kernel's zeroing of fresh pages (in a virtual machine
/// also the host's backing of them) then happens beside the parse instead of inside it.
///
/// `buffers` are `(address, capacity in bytes)` of buffers that are not reallocated
/// while `work` runs. `work` reports its progress through [`Progress::report`]: how
/// many bytes of each buffer are filled and what fraction of the input is done. The
/// helper keeps each buffer populated up to [`AHEAD`] bytes past its filled part, but
/// not past the size the progress so far predicts for the whole input (plus 3 %), so
/// the memory it adds beyond what the work will use stays small.
///
/// Only populating (`MADV_POPULATE_WRITE`, Linux 5.14) is asked of the kernel: it
/// never changes what the buffers hold. Where it is not available, or where threads
/// cannot be started, `work` simply runs alone.
pub fn prefault_while<R>(buffers: &[(usize, usize)], work: impl FnOnce(&Progress) -> R) -> R {
    let progress = Progress {
        filled: buffers.iter().map(|_| AtomicUsize::new(0)).collect(),
        done_per_mille: AtomicUsize::new(0),
        finished: AtomicBool::new(false),
    };
    if !cfg!(target_os = "linux") || buffers.is_empty() {
        return work(&progress);
    }
    std::thread::scope(|s| {
        let p = &progress;
        let helper =
            std::thread::Builder::new().spawn_scoped(s, move || populate_ahead(buffers, p));
        let r = work(p);
        p.finished.store(true, Ordering::Release);
        if let Ok(h) = helper {
            let _ = h.join();
        }
        r
    })
}

/// How far ahead of the filled part [`prefault_while`] populates a buffer.
pub const AHEAD: usize = 8 << 20;

/// Progress of the work in [`prefault_while`].
#[derive(Debug)]
pub struct Progress {
    filled: Vec<AtomicUsize>,
    done_per_mille: AtomicUsize,
    finished: AtomicBool,
}

impl Progress {
    /// `filled[k]`: bytes of buffer `k` written so far; `done`: fraction of the input
    /// consumed (0 to 1).
    pub fn report(&self, filled: &[usize], done: f64) {
        for (a, f) in self.filled.iter().zip(filled) {
            a.store(*f, Ordering::Relaxed);
        }
        let pm = (done.clamp(0.0, 1.0) * 1000.0) as usize;
        self.done_per_mille.store(pm, Ordering::Release);
    }
}

fn populate_ahead(buffers: &[(usize, usize)], p: &Progress) {
    const STEP: usize = 2 << 20;
    let mut populated: Vec<usize> = vec![0; buffers.len()];
    while !p.finished.load(Ordering::Acquire) {
        let done = p.done_per_mille.load(Ordering::Acquire);
        let mut worked = false;
        for (k, &(addr, cap)) in buffers.iter().enumerate() {
            let filled = p.filled[k].load(Ordering::Relaxed);
            // The whole buffer's likely size from the progress so far.
            let predicted = if done >= 20 {
                filled.saturating_mul(1030) / done
            } else {
                usize::MAX
            };
            let target = cap.min(filled.saturating_add(AHEAD)).min(predicted);
            let from = populated[k].max(filled);
            if from < target {
                let to = target.min(from + STEP);
                populate(addr + from, to - from);
                populated[k] = to;
                worked = true;
            }
        }
        if !worked {
            std::thread::sleep(std::time::Duration::from_micros(200));
        }
    }
}

/// Asks the kernel to fault in the pages of `[addr, addr + len)` for writing.
#[cfg(target_os = "linux")]
fn populate(addr: usize, len: usize) {
    let start = addr & !4095;
    let end = (addr + len + 4095) & !4095;
    // SAFETY: `MADV_POPULATE_WRITE` only faults pages in, as a write would, without
    // changing their contents; on a range that is no longer mapped it fails, which is
    // ignored.
    unsafe {
        libc::madvise(
            start as *mut libc::c_void,
            end - start,
            libc::MADV_POPULATE_WRITE,
        );
    }
}

#[cfg(not(target_os = "linux"))]
fn populate(_addr: usize, _len: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    /// Blocks of every kind keep their contents through growth and shrinking
    /// across the threshold, and come back zeroed when asked.
    #[test]
    fn blocks_survive_resizing_across_the_threshold() {
        let a = LargePages;
        let sizes = [
            64,
            LARGE - 1,
            LARGE,
            LARGE + 1,
            3 * LARGE + 12345,
            LARGE,
            100,
        ];
        unsafe {
            let mut layout = Layout::from_size_align(sizes[0], 8).unwrap();
            let mut p = a.alloc(layout);
            assert!(!p.is_null());
            for i in 0..layout.size() {
                *p.add(i) = (i % 251) as u8;
            }
            for &s in &sizes[1..] {
                let q = a.realloc(p, layout, s);
                assert!(!q.is_null());
                let kept = layout.size().min(s);
                for i in 0..kept {
                    assert_eq!(*q.add(i), (i % 251) as u8, "byte {i} after resizing to {s}");
                }
                for i in kept..s {
                    *q.add(i) = (i % 251) as u8;
                }
                layout = Layout::from_size_align(s, 8).unwrap();
                p = q;
            }
            a.dealloc(p, layout);

            let big = Layout::from_size_align(LARGE + 4096, 64).unwrap();
            let z = a.alloc_zeroed(big);
            assert!(!z.is_null());
            assert_eq!(z as usize % 64, 0);
            assert!((0..big.size()).step_by(997).all(|i| *z.add(i) == 0));
            a.dealloc(z, big);
        }
    }

    /// Once a large block has been mapped the allocator cannot be switched off
    /// (the block must be unmapped when freed); the tests above map blocks first.
    #[test]
    fn cannot_be_switched_off_after_mapping() {
        let a = LargePages;
        unsafe {
            let layout = Layout::from_size_align(LARGE, 8).unwrap();
            let p = a.alloc(layout);
            assert!(!p.is_null());
            assert!(!LargePages::disable());
            *p.add(LARGE - 1) = 1;
            a.dealloc(p, layout);
        }
    }

    /// A freed large block is kept and handed out again, whole and writable, at
    /// any size; zeroed blocks are zero even right after a block was freed.
    #[test]
    fn freed_blocks_come_back() {
        let a = LargePages;
        unsafe {
            for (first, second) in [(LARGE, LARGE), (3 * LARGE, LARGE + 1), (LARGE, 5 * LARGE)] {
                let l1 = Layout::from_size_align(first, 8).unwrap();
                let p = a.alloc(l1);
                assert!(!p.is_null());
                std::ptr::write_bytes(p, 0xAB, first);
                a.dealloc(p, l1);
                let l2 = Layout::from_size_align(second, 8).unwrap();
                let q = a.alloc(l2);
                assert!(!q.is_null());
                std::ptr::write_bytes(q, 0x11, second);
                assert!((0..second).step_by(4093).all(|i| *q.add(i) == 0x11));
                a.dealloc(q, l2);
                let z = a.alloc_zeroed(l2);
                assert!(!z.is_null());
                assert!((0..second).step_by(4093).all(|i| *z.add(i) == 0));
                a.dealloc(z, l2);
            }
        }
    }

    /// A vector that grows past the threshold by doubling, as the parser's do.
    #[test]
    fn vectors_grow_through_the_allocator() {
        let a = LargePages;
        unsafe {
            let mut layout = Layout::array::<u64>(1).unwrap();
            let mut p = a.alloc(layout) as *mut u64;
            *p = 7;
            let mut n = 1usize;
            while n * 8 < 4 * LARGE {
                let grown = Layout::array::<u64>(2 * n).unwrap();
                p = a.realloc(p as *mut u8, layout, grown.size()) as *mut u64;
                assert!(!p.is_null());
                for i in n..2 * n {
                    *p.add(i) = 7 + i as u64;
                }
                layout = grown;
                n *= 2;
            }
            assert!((0..n).all(|i| *p.add(i) == 7 + i as u64));
            a.dealloc(p as *mut u8, layout);
        }
    }
}
