//! The exit statuses of `lazysolid`, one per outcome a script may want to tell apart.

/// The command did what it was asked.
pub const SUCCESS: i32 = 0;
/// An error: bad arguments or input, a missing device or file, a failed build or write.
pub const ERROR: i32 = 1;
/// The command finished, but the Vulkan validation layer reported errors.
pub const VALIDATION: i32 = 2;
/// `diff --max-mean`: the images were compared and differ more than allowed.
pub const ABOVE_THRESHOLD: i32 = 3;

/// What `lazysolid --help` says about them.
pub const HELP: &str = "Exit status: 0 success; 1 error (bad arguments or input, missing device \
or file); 2 the Vulkan validation layer reported errors; 3 `diff --max-mean`: the mean FLIP \
error is above the threshold.";
