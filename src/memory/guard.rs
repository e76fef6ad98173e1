//! The binary's global allocator ([`Guarded`]): an allocation that fails
//! anyway, after the estimate said the run fits, ends the process with one
//! paragraph and exit status 1, not Rust's `memory allocation of N bytes failed` and an abort (134). On
//! stable Rust the allocation error hook (`std::alloc::set_alloc_error_hook`)
//! is unstable, so the check sits in the allocator itself: a thin wrapper
//! of the system allocator that, when it returns null, writes a fixed
//! message with `write(2)` (nothing allocated) and leaves with `_exit(1)`.
//! Results are committed in one step after everything was computed, so a
//! run stopped there has written nothing (its hidden staging directory, if
//! the commit was under way, is removed by the next run).

use std::alloc::{GlobalAlloc, Layout, System};

/// The system allocator, ending the process with one paragraph and exit
/// status 1 when an allocation fails (see the module header).
pub struct Guarded;

// SAFETY: every call goes to the system allocator unchanged; on failure
// the process ends before anything sees the null pointer.
unsafe impl GlobalAlloc for Guarded {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            out_of_memory(layout.size());
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if p.is_null() {
            out_of_memory(layout.size());
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            out_of_memory(new_size);
        }
        p
    }
}

/// Writes the out-of-memory paragraph to stderr and exits 1, allocating nothing.
fn out_of_memory(size: usize) -> ! {
    let mut digits = [0u8; 20];
    let mut i = digits.len();
    let mut v = size;
    loop {
        i -= 1;
        digits[i] = b'0' + (v % 10) as u8;
        v /= 10;
        if v == 0 {
            break;
        }
    }
    let parts: [&[u8]; 3] = [
        b"error: out of memory: an allocation of ",
        &digits[i..],
        b" bytes failed, so the run stopped; no result files were written (results are committed all at once, at the end). Give the run more memory, or make it smaller: --interface iterative (no dense interface matrices), --substructures K (smaller factors), more MPI ranks, or a coarser mesh (larger lc in [gmsh] setnumber)\n",
    ];
    for part in parts {
        // SAFETY: writes a valid buffer to stderr
        let _ = unsafe { libc::write(2, part.as_ptr().cast(), part.len()) };
    }
    // SAFETY: ends the process at once, running nothing that could allocate
    unsafe { libc::_exit(1) }
}
