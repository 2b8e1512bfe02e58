//! What every module of the test binary shares: the binary run with a clean environment, paths
//! in the repository, the outputs of a `lazysolid bench …` run and a small exemplar cut from the
//! assets.

use std::process::Command;

pub(crate) fn lazysolid() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_lazysolid"));
    c.env_remove("LAZYSOLID_DEVICE")
        .env_remove("LAZYSOLID_VALIDATION");
    c
}

/// A path in the repository (scenes, assets).
pub(crate) fn repo(path: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(path)
}

pub(crate) fn run(c: &mut Command) -> (bool, String, String) {
    let out = c.output().expect("lazysolid runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// What a `lazysolid bench …` run left behind: its standard output and the entries of its
/// `--out` folder (the CSV, the JSON and the figures folder).
pub(crate) struct BenchRun {
    pub(crate) stdout: String,
    pub(crate) entries: Vec<std::path::PathBuf>,
}

impl BenchRun {
    /// Runs `c` with `--out-dir out` and the validation layer on; it must succeed and print
    /// every one of `needles`.
    pub(crate) fn new(c: &mut Command, out: &std::path::Path, needles: &[&str]) -> BenchRun {
        let (ok, stdout, err) = run(c.arg("--out-dir").arg(out).env("LAZYSOLID_VALIDATION", "1"));
        assert!(ok, "{err}");
        for needle in needles {
            assert!(stdout.contains(needle), "missing {needle:?} in:\n{stdout}");
        }
        let entries = std::fs::read_dir(out)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        BenchRun { stdout, entries }
    }

    /// The one entry with extension `ext`.
    pub(crate) fn file(&self, ext: &str) -> &std::path::Path {
        self.entries
            .iter()
            .find(|p| p.extension().is_some_and(|e| e == ext))
            .unwrap_or_else(|| panic!("no .{ext} file in {:?}", self.entries))
    }

    /// The JSON file, parsed.
    pub(crate) fn json(&self) -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(self.file("json")).unwrap()).unwrap()
    }

    /// The CSV file: its header and its records, each checked to have the header's length
    /// (fields holding commas are quoted).
    pub(crate) fn csv(&self) -> (csv::StringRecord, Vec<csv::StringRecord>) {
        let mut reader = csv::Reader::from_path(self.file("csv")).unwrap();
        let header = reader.headers().unwrap().clone();
        let records: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();
        for r in &records {
            assert_eq!(r.len(), header.len(), "{r:?} against {header:?}");
        }
        (header, records)
    }

    /// The values of column `name` in every record.
    pub(crate) fn column(&self, name: &str) -> Vec<String> {
        let (header, records) = self.csv();
        let i = header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
        records.iter().map(|r| r[i].to_string()).collect()
    }

    /// The figures folder.
    pub(crate) fn figures(&self) -> &std::path::Path {
        self.entries
            .iter()
            .find(|p| p.is_dir())
            .expect("a figures folder")
    }

    /// The file names in the figures folder.
    pub(crate) fn figure_names(&self) -> Vec<String> {
        std::fs::read_dir(self.figures())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect()
    }
}

/// A `side`² PNG cut from the top-left of GIMP's terra pattern, in `dir`.
pub(crate) fn terra_square(dir: &std::path::Path, side: u32) -> std::path::PathBuf {
    let full = image::open(repo("assets/exemplars/terra.pat"))
        .map(|i| i.to_rgb8())
        .unwrap_or_else(|_| {
            // The image crate does not read GIMP patterns: decode through the library.
            let e = lazysolid_synth::Exemplar::load(&repo("assets/exemplars/terra.pat")).unwrap();
            image::RgbImage::from_fn(e.width, e.height, |x, y| image::Rgb(e.at(x, y)))
        });
    let path = dir.join(format!("terra{side}.png"));
    image::imageops::crop_imm(&full, 0, 0, side, side)
        .to_image()
        .save(&path)
        .unwrap();
    path
}

/// The 64-bit FNV-1a digest of `bytes`: how the tests pin outputs that must stay byte for
/// byte what they were.
pub(crate) fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}
