//! Comma-separated coordinates on the command line (`--offset -512,1024`, `--center 0.3,0.6`,
//! `--offset -64,0,128`): one parser for every such option, so they all accept and refuse the
//! same way.

use std::str::FromStr;

/// `s` as exactly `N` comma-separated values (X,Y or X,Y,Z). Errors quote the whole value and,
/// for a bad component, that component; `example` (e.g. `" (e.g. -512,1024)"`) follows the
/// expected form and `kind` names what a component must be.
pub fn components<T: FromStr, const N: usize>(
    s: &str,
    example: &str,
    kind: &str,
) -> Result<[T; N], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != N {
        let names = ["X", "Y", "Z", "W"][..N.min(4)].join(",");
        return Err(format!("{s:?} is not {names}{example}"));
    }
    let mut out = Vec::with_capacity(N);
    for v in parts {
        out.push(
            v.trim()
                .parse()
                .map_err(|_| format!("{v:?} in {s:?} is not {kind}"))?,
        );
    }
    Ok(out
        .try_into()
        .unwrap_or_else(|_| unreachable!("{N} parts were checked")))
}

#[cfg(test)]
mod tests {
    use super::components;

    #[test]
    fn pairs_and_triples_parse_and_bad_ones_are_named() {
        assert_eq!(
            components::<i32, 2>("-512, 1024", "", "a whole number"),
            Ok([-512, 1024])
        );
        assert_eq!(
            components::<f64, 2>("0.5,1", "", "a number"),
            Ok([0.5, 1.0])
        );
        assert_eq!(
            components::<i32, 3>("1,2,3", "", "a whole number"),
            Ok([1, 2, 3])
        );
        assert_eq!(
            components::<i32, 2>("1,2,3", " (e.g. -512,1024)", "a whole number"),
            Err("\"1,2,3\" is not X,Y (e.g. -512,1024)".into())
        );
        assert_eq!(
            components::<i32, 2>("1,x", "", "a whole number"),
            Err("\"x\" in \"1,x\" is not a whole number".into())
        );
    }
}
