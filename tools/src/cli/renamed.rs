//! Flags that were renamed when every subcommand got one word per thing (`docs/usage.md`,
//! "One word per thing"): the parser refuses the old spelling, and this table names the new
//! one, so a script written for an older build gets told what to write instead of only
//! "unexpected argument".

/// `(subcommand, old, new)`; `*` for a rename that holds wherever the old flag was accepted.
const RENAMED: [(&str, &str, &str); 19] = [
    ("solid", "--size", "--voxel-res"),
    ("bench solid", "--sizes", "--voxel-res"),
    ("bench solid", "--builders", "--candidates"),
    ("multiscale", "--size", "--res"),
    ("zoom", "--size", "--res"),
    ("zoom", "-o", "--out-dir"),
    ("zoom", "--output", "--out-dir"),
    ("zoom", "--frames", "--frame-count"),
    ("fracture", "-o", "--out-dir"),
    ("bench multiscale", "--size", "--res"),
    ("bench multiscale", "--quality-size", "--quality-res"),
    ("synth", "--size", "--res"),
    ("bench synth", "--sizes", "--res"),
    ("bench textures", "--view", "--res"),
    ("*", "--voxel-resolution", "--voxel-res"),
    ("*", "--voxel-resolutions", "--voxel-res"),
    ("*", "--image-size", "--image-res"),
    ("*", "--blocked-resolution", "--blocked-voxel-res"),
    ("*", "--out", "--out-dir"),
];

/// The subcommand `args` (the command line without the program) runs: `bench NAME` or the
/// first word that is not a flag.
fn subcommand(args: &[String]) -> String {
    let mut words = args.iter().filter(|a| !a.starts_with('-'));
    match words.next().map(String::as_str) {
        Some("bench") => format!("bench {}", words.next().map_or("", |w| w.as_str())),
        Some(word) => word.to_string(),
        None => String::new(),
    }
}

/// The line that names the new spelling of `flag`, refused by the parser in `args`, when
/// `flag` is a renamed one.
pub fn hint(args: &[String], flag: &str) -> Option<String> {
    let command = subcommand(args);
    // The flag as typed, without an `=value`.
    let flag = flag.split('=').next().unwrap_or(flag);
    RENAMED
        .iter()
        .find(|(c, old, _)| *old == flag && (*c == command || *c == "*"))
        .map(|(_, old, new)| format!("note: `{old}` is now `{new}` (lazysolid {command} --help)"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn the_new_spelling_is_named_per_subcommand() {
        assert_eq!(
            hint(&args("solid leather --size 64"), "--size").unwrap(),
            "note: `--size` is now `--voxel-res` (lazysolid solid --help)"
        );
        assert!(hint(&args("zoom g.toml --size 64"), "--size")
            .unwrap()
            .contains("`--res`"));
        assert!(hint(&args("bench solid --sizes 64"), "--sizes")
            .unwrap()
            .contains("`--voxel-res`"));
        assert!(hint(&args("bench hash --image-size=64"), "--image-size=64")
            .unwrap()
            .contains("`--image-res`"));
        assert_eq!(hint(&args("render s.toml --size 64"), "--size"), None);
        assert_eq!(hint(&args("solid leather --nope"), "--nope"), None);
    }
}
