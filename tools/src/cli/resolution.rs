//! `--res`: the width and height in pixels of every image a subcommand makes.

use std::fmt;
use std::str::FromStr;

/// Largest side any subcommand accepts; each may allow less.
const MAX_SIDE: u32 = 16384;

/// Pixels per row and per column, written `WxH` (`N` is short for `NxN`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Resolution {
    pub width: u32,
    pub height: u32,
}

impl Resolution {
    /// A square of `side` pixels.
    pub const fn square(side: u32) -> Resolution {
        Resolution {
            width: side,
            height: side,
        }
    }

    /// The side of a square resolution; `flag` and `what` name it when it is not square.
    pub fn side(self, flag: &str, what: &str) -> anyhow::Result<u32> {
        anyhow::ensure!(
            self.width == self.height,
            "{flag} {self}: {what} is square (give N or NxN)"
        );
        Ok(self.width)
    }

    /// Fails unless both sides lie in `range`, naming `flag`.
    pub fn check(self, flag: &str, range: std::ops::RangeInclusive<u32>) -> anyhow::Result<()> {
        anyhow::ensure!(
            range.contains(&self.width) && range.contains(&self.height),
            "{flag} {self} is out of range ({}..={} per side)",
            range.start(),
            range.end()
        );
        Ok(())
    }
}

impl fmt::Display for Resolution {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{}", self.width, self.height)
    }
}

impl FromStr for Resolution {
    type Err = String;

    fn from_str(s: &str) -> Result<Resolution, String> {
        let parse = |v: &str, what: &str| -> Result<u32, String> {
            let n: u32 = v.trim().parse().map_err(|_| {
                format!("{what} {v:?} in {s:?} is not a whole number (expected WxH, e.g. 640x480)")
            })?;
            if !(1..=MAX_SIDE).contains(&n) {
                return Err(format!(
                    "{what} {n} in {s:?} is out of range (1..={MAX_SIDE})"
                ));
            }
            Ok(n)
        };
        match s.split_once(['x', 'X']) {
            Some((w, h)) => Ok(Resolution {
                width: parse(w, "width")?,
                height: parse(h, "height")?,
            }),
            None => parse(s, "side").map(Resolution::square),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_wxh_and_square_sides_and_names_bad_parts() {
        assert_eq!(
            "640x480".parse(),
            Ok(Resolution {
                width: 640,
                height: 480
            })
        );
        assert_eq!("64".parse(), Ok(Resolution::square(64)));
        let e = "40by30".parse::<Resolution>().unwrap_err();
        assert!(e.contains("WxH") && e.contains("40by30"), "{e}");
        let e = "0x30".parse::<Resolution>().unwrap_err();
        assert!(e.contains("width 0") && e.contains("out of range"), "{e}");
        assert_eq!(Resolution::square(8).to_string(), "8x8");
        assert!(Resolution {
            width: 8,
            height: 4
        }
        .side("--res", "the view")
        .is_err());
    }
}
