//! The help of the tool and of every subcommand: one word and one value form per thing, and none
//! of the flags' old spellings.

use crate::support::{lazysolid, run};

/// The help of the tool and of every subcommand.
fn every_help() -> Vec<(String, String)> {
    let commands: [&[&str]; 21] = [
        &[],
        &["device"],
        &["diff"],
        &["render"],
        &["synth"],
        &["multiscale"],
        &["zoom"],
        &["fracture"],
        &["solid"],
        &["bench", "prims"],
        &["bench", "hash"],
        &["bench", "psh"],
        &["bench", "trace"],
        &["bench", "synth"],
        &["bench", "textures"],
        &["bench", "glints"],
        &["bench", "normalmaps"],
        &["bench", "solid"],
        &["bench", "lazy"],
        &["bench", "cuts"],
        &["bench", "multiscale"],
    ];
    commands
        .iter()
        .map(|c| {
            let (ok, help, err) = run(lazysolid().args(*c).arg("--help"));
            assert!(ok, "{c:?}: {err}");
            (c.join(" "), help)
        })
        .collect()
}

#[test]
fn every_help_uses_one_word_and_one_value_form_per_thing() {
    // Flag → value name, over every subcommand: one form per flag.
    let mut forms: std::collections::BTreeMap<String, std::collections::BTreeSet<String>> =
        Default::default();
    for (command, help) in every_help() {
        // Flag lines only (`  -o, --output <OUTPUT>`), not flags named in prose.
        for line in help.lines().filter(|l| l.trim_start().starts_with('-')) {
            // The flags and their value names lead the line; the description after them may
            // name other flags in prose (`... from --seed`).
            let words: Vec<&str> = line
                .split_whitespace()
                .take_while(|w| w.starts_with('-') || w.starts_with('<'))
                .collect();
            for (i, w) in words.iter().enumerate() {
                let flag = w.trim_end_matches(',');
                if flag.starts_with("--") && flag.len() > 2 {
                    let value = words
                        .get(i + 1)
                        .filter(|v| v.starts_with('<'))
                        .map_or("(switch)", |v| v);
                    forms
                        .entry(flag.to_string())
                        .or_default()
                        .insert(value.to_string());
                }
            }
        }
        for old in [
            "--view",
            "--size ",
            "--sizes",
            "--voxel-resolution",
            "--image-size",
            "--blocked-resolution",
            "--out <",
            "--quality-size",
        ] {
            assert!(!help.contains(old), "`{command}` still says {old}:\n{help}");
        }
    }
    for (flag, values) in &forms {
        assert_eq!(values.len(), 1, "{flag} is written {values:?}");
    }
    let form = |flag: &str| forms[flag].iter().next().unwrap().clone();
    assert_eq!(form("--res"), "<WxH>");
    assert_eq!(form("--image-res"), "<WxH>");
    assert_eq!(form("--voxel-res"), "<N>");
    assert_eq!(form("--mesh"), "<NAME|PATH>");
    assert_eq!(form("--exemplars"), "<NAME|PATH>");
    assert_eq!(form("--out-dir"), "<DIR>");
    assert_eq!(form("--builder"), "<BUILDER>");
    assert_eq!(form("--validation"), "(switch)");
}
