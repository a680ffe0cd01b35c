//! Zeroed buffers for large results, backed by transparent huge pages where the operating
//! system offers them.
//!
//! A result that does not fit in memory the allocator already holds comes from new pages of
//! the operating system, and every 4 KiB page costs a fault on first touch. On the 2-core VM of
//! `docs/performance.md` that is 1.5–2.6 µs a page: a 3-D cubic interpolation of 10^6 points
//! writes 48 MB of new memory and spent as long in the kernel's page faults (about 25 ns a
//! point) as in its arithmetic. With one fault per 2 MiB the same memory costs about a third.
//!
//! So a buffer of [`HUGE_PAGE_THRESHOLD`] bytes or more is allocated zeroed (`calloc`, which
//! for such sizes maps fresh zero pages and touches none of them) and, on Linux, the 2 MiB
//! aligned part of it is marked `MADV_HUGEPAGE` before anything is written. This is what NumPy
//! does for its arrays of 4 MiB and more, and what glibc's `glibc.malloc.hugetlb=1` tunable
//! does for a whole process. The hint changes how the kernel backs the pages, never their
//! contents; where transparent huge pages are off (`/sys/kernel/mm/transparent_hugepage/
//! enabled` = `never`) or unsupported it does nothing.

/// Buffers of at least this many bytes (4 MiB, NumPy's choice) are offered huge pages.
pub(crate) const HUGE_PAGE_THRESHOLD: usize = 4 << 20;

/// The huge page size the hint is aligned to (x86-64 and 4 KiB-page aarch64).
const HUGE_PAGE: usize = 2 << 20;

/// `len` zeros (`T::default()` must be the all-zero bit pattern, as for `f64` and arrays of
/// it, for the allocation to be `calloc`'s untouched zero pages), with the huge-page hint for
/// large sizes.
pub(crate) fn zeroed<T: Copy + Default>(len: usize) -> Vec<T> {
    let mut buf = vec![T::default(); len];
    if std::mem::size_of_val(buf.as_slice()) >= HUGE_PAGE_THRESHOLD {
        advise_huge_pages(&mut buf);
    }
    buf
}

/// An empty vector with room for `len` values, with the huge-page hint for large sizes
/// (`Vec::with_capacity` touches none of its spare room, so the hint comes before any write).
pub(crate) fn with_capacity<T>(len: usize) -> Vec<T> {
    let mut buf = Vec::with_capacity(len);
    if len * std::mem::size_of::<T>() >= HUGE_PAGE_THRESHOLD {
        advise_huge_pages(buf.spare_capacity_mut());
    }
    buf
}

/// A buffer of `len` numbers for a result: `held`'s storage if it has the capacity (its old
/// contents kept, only the growth written: every entry is overwritten by the caller), else
/// [`zeroed`]. `resize` on a new, empty vector would write every zero itself, a whole extra
/// sweep over memory that is about to be overwritten, and would touch the pages before the
/// huge-page hint.
pub(crate) fn reuse_or_zeroed<T: Copy + Default>(held: &mut Vec<T>, len: usize) -> Vec<T> {
    if held.capacity() >= len {
        let mut buf = std::mem::take(held);
        buf.resize(len, T::default());
        buf
    } else {
        zeroed(len)
    }
}

/// Marks the 2 MiB-aligned part of `buf` `MADV_HUGEPAGE`.
#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn advise_huge_pages<T>(buf: &mut [T]) {
    let start = buf.as_mut_ptr() as usize;
    let end = start + std::mem::size_of_val(buf);
    let first = start.next_multiple_of(HUGE_PAGE);
    let last = end - end % HUGE_PAGE;
    if last > first {
        // SAFETY: `madvise` reads and writes no memory of ours. The range [first, last) lies
        // inside `buf`, which this function borrows mutably, so no other reference can observe
        // the call, and MADV_HUGEPAGE only changes how the kernel backs those pages, never their
        // contents. `first` is 2 MiB-aligned, hence page-aligned as `madvise` requires. The
        // result is ignored on purpose: a failure (EINVAL where transparent huge pages are not
        // built in) leaves the ordinary pages, which is correct, only slower.
        unsafe {
            libc::madvise(
                first as *mut libc::c_void,
                last - first,
                libc::MADV_HUGEPAGE,
            );
        }
    }
}

/// No hint where there is no `madvise`.
#[cfg(not(target_os = "linux"))]
fn advise_huge_pages<T>(_buf: &mut [T]) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_and_small_buffers_are_zero_and_sized() {
        for len in [
            0,
            1,
            1000,
            HUGE_PAGE_THRESHOLD / 8 - 1,
            3 * HUGE_PAGE_THRESHOLD / 8 + 5,
        ] {
            let buf: Vec<f64> = zeroed(len);
            assert_eq!(buf.len(), len, "length");
            assert!(
                buf.iter().all(|v| v.to_bits() == 0),
                "zeros at length {len}"
            );
            let pairs: Vec<[f64; 2]> = zeroed(len / 2);
            assert!(pairs.iter().all(|v| *v == [0.0; 2]), "zero pairs");
        }
    }

    #[test]
    fn held_storage_is_reused_and_fresh_storage_is_zero() {
        let mut held = vec![7.0_f64; 10];
        let ptr = held.as_ptr();
        let buf = reuse_or_zeroed(&mut held, 12);
        // not enough room: a new zeroed buffer, `held` untouched
        assert_eq!(buf, vec![0.0; 12], "fresh zeros");
        assert_eq!(held.len(), 10, "held kept");
        let buf = reuse_or_zeroed(&mut held, 8);
        assert_eq!(buf.as_ptr(), ptr, "held storage reused");
        assert_eq!(
            buf,
            vec![7.0; 8],
            "old contents kept (the caller overwrites them)"
        );
        assert!(held.is_empty(), "taken out of the workspace");
    }

    /// The `VmFlags` line of the mapping of `/proc/self/smaps` that contains `addr`.
    #[cfg(target_os = "linux")]
    fn vm_flags(addr: usize) -> Option<String> {
        let smaps = std::fs::read_to_string("/proc/self/smaps").ok()?;
        let mut inside = false;
        for line in smaps.lines() {
            let range = line
                .split_whitespace()
                .next()
                .and_then(|r| r.split_once('-'));
            if let Some((a, b)) = range {
                if let (Ok(a), Ok(b)) = (usize::from_str_radix(a, 16), usize::from_str_radix(b, 16))
                {
                    inside = (a..b).contains(&addr);
                    continue;
                }
            }
            if inside && line.starts_with("VmFlags:") {
                return Some(line.to_string());
            }
        }
        None
    }

    /// The kernel records `MADV_HUGEPAGE` as the mapping's `hg` flag, whether or not huge pages
    /// are free at the moment: a deterministic check that the hint is given.
    #[cfg(target_os = "linux")]
    #[test]
    fn large_buffers_carry_the_huge_page_flag() {
        if !std::path::Path::new("/sys/kernel/mm/transparent_hugepage/enabled").exists() {
            return; // a kernel without transparent huge pages: nothing to check
        }
        // whether the mapping holding the first 2 MiB-aligned address at or after `ptr` is
        // marked, and its flags for the message
        let hinted = |ptr: *const f64| {
            let flags = vm_flags((ptr as usize).next_multiple_of(HUGE_PAGE))
                .expect("the buffer's mapping in /proc/self/smaps");
            (flags.split_whitespace().any(|f| f == "hg"), flags)
        };
        let big: Vec<f64> = zeroed(2 * HUGE_PAGE_THRESHOLD / 8);
        let (marked, flags) = hinted(big.as_ptr());
        assert!(marked, "no hint: {flags}");
        let grown: Vec<f64> = with_capacity(2 * HUGE_PAGE_THRESHOLD / 8);
        let (marked, flags) = hinted(grown.as_ptr());
        assert!(marked, "no hint on reserve: {flags}");
        let small: Vec<f64> = zeroed(1000);
        let flags = vm_flags(small.as_ptr() as usize).expect("the small buffer's mapping");
        assert!(
            !flags.split_whitespace().any(|f| f == "hg"),
            "small buffer hinted: {flags}"
        );
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn the_hint_leaves_contents_alone() {
        let mut buf: Vec<f64> = zeroed(HUGE_PAGE_THRESHOLD);
        for (i, v) in buf.iter_mut().enumerate() {
            *v = i as f64;
        }
        advise_huge_pages(&mut buf);
        assert!(
            buf.iter().enumerate().all(|(i, v)| *v == i as f64),
            "contents changed"
        );
    }
}
