//! How the candidate kernels split their work under llvmpipe's loop limit. llvmpipe (the
//! shader compiler of lavapipe) gives each invocation one counter of 65535 loop iterations,
//! shared by all of its loops and decremented at every pass through a loop's end, including
//! the pass that leaves the loop; once it runs out every loop exits early without any error,
//! which silently truncates a search. The host therefore splits a search into dispatches whose
//! worst case stays under a budget below the limit, and each dispatch folds its results into
//! those of the previous ones.

use crate::{SynthError, SynthResult};

/// llvmpipe's loop iterations per invocation (`LP_MAX_TGSI_LOOP_ITERATIONS`).
pub const LOOP_LIMIT: u32 = 65535;

/// The iterations one dispatch is planned to by default: a margin under [`LOOP_LIMIT`] for the
/// loops a plan does not count one by one (constant-trip loops the compiler may keep).
pub const LOOP_BUDGET: u32 = 60_000;

const _: () = assert!(LOOP_BUDGET < LOOP_LIMIT);

/// Iterations of a loop of at most `trips` trips (one more for the pass that leaves it).
pub fn loop_cost(trips: u32) -> u32 {
    trips + 1
}

/// How many items of worst-case cost `per_item` one dispatch planned to `budget` iterations
/// can take after `overhead` iterations spent outside the items' loop.
///
/// # Errors
/// [`SynthError::Parameter`] when `budget` exceeds [`LOOP_BUDGET`] or cannot hold one item.
pub fn items_per_dispatch(budget: u32, per_item: u32, overhead: u32) -> SynthResult<u32> {
    if budget > LOOP_BUDGET || overhead + per_item > budget {
        return Err(SynthError::Parameter {
            name: "loop budget",
            value: budget.to_string(),
            limit: format!(
                "must hold one item of {per_item} loop iterations after {overhead} and stay within {LOOP_BUDGET} (llvmpipe stops an invocation after {LOOP_LIMIT})"
            ),
        });
    }
    Ok((budget - overhead) / per_item)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn items_fill_the_budget_without_passing_it() {
        let n = items_per_dispatch(LOOP_BUDGET, 71, 140).unwrap();
        assert!(140 + n * 71 <= LOOP_BUDGET);
        assert!(140 + (n + 1) * 71 > LOOP_BUDGET);
        assert_eq!(items_per_dispatch(1000, 1000, 0).unwrap(), 1);
    }

    #[test]
    fn a_budget_that_holds_no_item_or_passes_the_limit_is_refused() {
        let e = items_per_dispatch(1000, 1000, 1).unwrap_err().to_string();
        assert!(e.contains("loop budget") && e.contains("1000"), "{e}");
        let e = items_per_dispatch(LOOP_LIMIT, 10, 0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("60000"), "{e}");
    }
}
