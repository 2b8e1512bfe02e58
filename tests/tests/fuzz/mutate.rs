//! Mutations of a valid file, the inputs of every fuzz test: a few edits of its bytes (flipped
//! bits, set bytes, header words set to boundary values, cuts, deletions, insertions,
//! repetitions) or of its text (numbers replaced by boundary values, lines deleted, repeated or
//! swapped). Drawn by proptest, so a failing case shrinks to the fewest, smallest edits.

use proptest::prelude::*;

/// Words a size or count field is set to: zero, one, the powers of two around the readers'
/// limits, and the values that overflow 16, 32 and signed 32-bit arithmetic.
const WORDS: &[u32] = &[
    0,
    1,
    2,
    3,
    4,
    7,
    8,
    255,
    256,
    4096,
    8192,
    8193,
    65_535,
    65_536,
    1 << 20,
    0x7fff_ffff,
    0x8000_0000,
    0xffff_ffff,
];

/// What a number in a text file is replaced by: signs, zero, fractions where integers belong,
/// values past every integer width, non-finite and malformed numbers, and nothing at all.
const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "1",
    "-1",
    "2",
    "3",
    "0.5",
    "-2.5",
    "1e-40",
    "1e39",
    "-1e39",
    "65536",
    "2147483648",
    "4294967295",
    "4294967296",
    "18446744073709551616",
    "99999999999999999999999",
    "nan",
    "inf",
    "-inf",
    "1..2",
    "0x10",
    "",
];

/// What a line-level mutation does to the line it picks.
#[derive(Clone, Copy, Debug)]
pub enum LineEdit {
    /// Removes it.
    Delete,
    /// Writes it twice.
    Repeat,
    /// Exchanges it with the next line.
    SwapWithNext,
    /// Keeps its first half only.
    CutInHalf,
}

/// One edit of a file. Positions are taken modulo the file's length (plus one where the end
/// is a position), so every drawn edit applies to every file.
#[derive(Clone, Debug)]
pub enum Mutation {
    /// Inverts one bit.
    FlipBit { at: usize, bit: u8 },
    /// Sets one byte.
    SetByte { at: usize, value: u8 },
    /// Sets four bytes in the first 64 (where headers keep their fields) to a boundary word.
    SetHeaderWord {
        at: usize,
        word: u32,
        big_endian: bool,
    },
    /// Drops everything from a position on.
    Truncate { at: usize },
    /// Removes up to `len` bytes.
    Delete { at: usize, len: usize },
    /// Inserts bytes.
    Insert { at: usize, bytes: Vec<u8> },
    /// Repeats a stretch of up to `len` bytes `times` times.
    Repeat { at: usize, len: usize, times: usize },
    /// Replaces the `nth` number of the text (counted modulo the numbers there are).
    Number { nth: usize, text: &'static str },
    /// Edits the `nth` line (modulo the lines there are).
    Line { nth: usize, edit: LineEdit },
    /// Inserts a line of the format's dictionary before the `nth` line: a field or keyword
    /// the seed may not have, with a boundary value.
    InsertLine { nth: usize, line: String },
}

/// The bytes of `file` after `mutations`, in order.
pub fn apply(file: &[u8], mutations: &[Mutation]) -> Vec<u8> {
    let mut bytes = file.to_vec();
    for m in mutations {
        apply_one(&mut bytes, m);
    }
    bytes
}

fn apply_one(bytes: &mut Vec<u8>, m: &Mutation) {
    let len = bytes.len();
    let within = |at: usize| if len == 0 { 0 } else { at % len };
    match *m {
        Mutation::FlipBit { at, bit } if len > 0 => bytes[within(at)] ^= 1 << (bit % 8),
        Mutation::SetByte { at, value } if len > 0 => bytes[within(at)] = value,
        Mutation::SetHeaderWord {
            at,
            word,
            big_endian,
        } if len >= 4 => {
            let at = at % (len.min(64) - 3);
            let w = if big_endian {
                word.to_be_bytes()
            } else {
                word.to_le_bytes()
            };
            bytes[at..at + 4].copy_from_slice(&w);
        }
        Mutation::Truncate { at } => bytes.truncate(at % (len + 1)),
        Mutation::Delete { at, len: n } if len > 0 => {
            let at = within(at);
            bytes.drain(at..(at + n).min(len));
        }
        Mutation::Insert {
            at,
            bytes: ref inserted,
        } => {
            let at = at % (len + 1);
            bytes.splice(at..at, inserted.iter().copied());
        }
        Mutation::Repeat { at, len: n, times } if len > 0 => {
            let at = within(at);
            let stretch = bytes[at..(at + n).min(len)].to_vec();
            for _ in 0..times {
                bytes.splice(at..at, stretch.iter().copied());
            }
        }
        Mutation::Number { nth, text } => {
            let numbers = number_spans(bytes);
            if !numbers.is_empty() {
                let (start, end) = numbers[nth % numbers.len()];
                bytes.splice(start..end, text.bytes());
            }
        }
        Mutation::Line { nth, edit } => edit_line(bytes, nth, edit),
        Mutation::InsertLine { nth, ref line } => {
            let mut lines: Vec<Vec<u8>> =
                bytes.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
            let k = nth % (lines.len() + 1);
            lines.insert(k, line.as_bytes().to_vec());
            *bytes = lines.join(&b'\n');
        }
        _ => {}
    }
}

/// The byte ranges of the numbers in a text: a digit, or a sign or point before one, then
/// digits, points, exponents and signs after an exponent.
fn number_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = bytes[i].is_ascii_digit()
            || (matches!(bytes[i], b'-' | b'+' | b'.')
                && bytes.get(i + 1).is_some_and(u8::is_ascii_digit));
        let inside_word = i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
        if !starts || inside_word {
            i += 1;
            continue;
        }
        let start = i;
        i += 1;
        while i < bytes.len() {
            let c = bytes[i];
            let exponent_sign = matches!(c, b'-' | b'+') && matches!(bytes[i - 1], b'e' | b'E');
            if c.is_ascii_digit() || matches!(c, b'.' | b'e' | b'E') || exponent_sign {
                i += 1;
            } else {
                break;
            }
        }
        spans.push((start, i));
    }
    spans
}

fn edit_line(bytes: &mut Vec<u8>, nth: usize, edit: LineEdit) {
    let mut lines: Vec<Vec<u8>> = bytes.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
    let k = nth % lines.len();
    match edit {
        LineEdit::Delete => {
            lines.remove(k);
        }
        LineEdit::Repeat => lines.insert(k, lines[k].clone()),
        LineEdit::SwapWithNext => {
            let next = (k + 1) % lines.len();
            lines.swap(k, next);
        }
        LineEdit::CutInHalf => {
            let half = lines[k].len() / 2;
            lines[k].truncate(half);
        }
    }
    *bytes = lines.join(&b'\n');
}

/// One edit, byte- or text-level, with boundary values preferred over uniform ones.
fn mutation() -> BoxedStrategy<Mutation> {
    let at = any::<usize>();
    prop_oneof![
        (at, 0u8..8).prop_map(|(at, bit)| Mutation::FlipBit { at, bit }),
        (
            at,
            prop_oneof![Just(0u8), Just(0xff), Just(0x7f), Just(0x80), any::<u8>()]
        )
            .prop_map(|(at, value)| Mutation::SetByte { at, value }),
        (at, prop::sample::select(WORDS), any::<bool>()).prop_map(|(at, word, big_endian)| {
            Mutation::SetHeaderWord {
                at,
                word,
                big_endian,
            }
        }),
        at.prop_map(|at| Mutation::Truncate { at }),
        (at, 1usize..64).prop_map(|(at, len)| Mutation::Delete { at, len }),
        (at, prop::collection::vec(any::<u8>(), 1..24))
            .prop_map(|(at, bytes)| Mutation::Insert { at, bytes }),
        (at, 1usize..32, 1usize..6).prop_map(|(at, len, times)| Mutation::Repeat {
            at,
            len,
            times
        }),
        (at, prop::sample::select(NUMBERS)).prop_map(|(nth, text)| Mutation::Number { nth, text }),
        (
            at,
            prop_oneof![
                Just(LineEdit::Delete),
                Just(LineEdit::Repeat),
                Just(LineEdit::SwapWithNext),
                Just(LineEdit::CutInHalf)
            ]
        )
            .prop_map(|(nth, edit)| Mutation::Line { nth, edit }),
    ]
    .boxed()
}

/// One to four edits.
pub fn mutations() -> impl Strategy<Value = Vec<Mutation>> {
    prop::collection::vec(mutation(), 1..=4)
}

/// One to four edits, a third of them insertions of a line of `dictionary` (the fields and
/// keywords of a text format, with boundary values).
pub fn mutations_with(dictionary: Vec<String>) -> impl Strategy<Value = Vec<Mutation>> {
    let insert = (any::<usize>(), prop::sample::select(dictionary))
        .prop_map(|(nth, line)| Mutation::InsertLine { nth, line });
    prop::collection::vec(prop_oneof![2 => mutation(), 1 => insert], 1..=4)
}

/// Values a field of a TOML file is set to by a dictionary line: every number of
/// [`NUMBERS`], and strings, booleans, arrays and tables of the wrong and right shapes.
pub fn toml_values() -> Vec<String> {
    let mut values: Vec<String> = NUMBERS
        .iter()
        .filter(|n| !n.is_empty() && !n.contains(".."))
        .map(|n| n.to_string())
        .collect();
    values.extend(
        [
            "\"\"",
            "\"x\"",
            "\"../nowhere.png\"",
            "true",
            "[]",
            "[0.0, 1.0]",
            "[1.0, 2.0, 3.0]",
            "[1e39, 0.0, -1.0]",
            "[\"a\", 1]",
            "{}",
            "{ kind = \"volume\" }",
            "0..8",
        ]
        .map(String::from),
    );
    values
}

/// `key = value` for every key and every [`toml_values`] value, and the table headers.
pub fn toml_dictionary(keys: &[&str], tables: &[&str]) -> Vec<String> {
    let values = toml_values();
    let mut lines: Vec<String> = keys
        .iter()
        .flat_map(|k| values.iter().map(move |v| format!("{k} = {v}")))
        .collect();
    lines.extend(tables.iter().map(|t| t.to_string()));
    lines
}

#[test]
fn the_edits_do_what_they_say() {
    let text = b"a 12\nsize: -3.5e+2 7\nend".to_vec();
    assert_eq!(
        number_spans(&text),
        vec![(2, 4), (11, 18), (19, 20)],
        "12, -3.5e+2 and 7"
    );
    let m = |m| apply(&text, &[m]);
    assert_eq!(
        m(Mutation::Number {
            nth: 1,
            text: "nan"
        }),
        b"a 12\nsize: nan 7\nend"
    );
    assert_eq!(
        m(Mutation::Line {
            nth: 1,
            edit: LineEdit::SwapWithNext
        }),
        b"a 12\nend\nsize: -3.5e+2 7"
    );
    assert_eq!(m(Mutation::Truncate { at: 4 }), b"a 12");
    assert_eq!(
        m(Mutation::SetHeaderWord {
            at: 0,
            word: 0x0102_0304,
            big_endian: true
        })[..4],
        [1, 2, 3, 4]
    );
    assert_eq!(m(Mutation::FlipBit { at: 0, bit: 0 })[0], b'a' ^ 1);
    assert_eq!(apply(b"", &[Mutation::FlipBit { at: 3, bit: 1 }]), b"");
}

/// Recomputes the checksum of every whole chunk of a PNG, so that edits of its header and data
/// reach the decoder instead of stopping at the checksum (the `png` crate checks it). Bytes
/// that do not parse as chunks are left as they are.
pub fn fix_png_checksums(bytes: &mut [u8]) {
    let mut at = 8;
    while at + 12 <= bytes.len() {
        let len = u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        let Some(end) = (at + 8).checked_add(len).filter(|&e| e + 4 <= bytes.len()) else {
            break;
        };
        let crc = crc32fast::hash(&bytes[at + 4..end]);
        bytes[end..end + 4].copy_from_slice(&crc.to_be_bytes());
        at = end + 4;
    }
}
