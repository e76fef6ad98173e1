//! Memory, known before it runs out: what a run will need at its peak,
//! estimated before any factorisation (`estimate.rs`), against what the
//! machine lets this process use (`machine.rs`); and the global allocator
//! that turns an allocation failing anyway into one paragraph and exit
//! status 1 (`guard.rs`).

mod estimate;
mod guard;
mod machine;

pub use estimate::{check, estimate, Estimate, TooLarge};
pub use guard::Guarded;
pub use machine::{available, give_back, human, peak, physical, resident, Available};
