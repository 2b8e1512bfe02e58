//! Exemplar graphs (Han et al. 2008, §3.1): exemplars linked by directed edges `(i, j, r)`
//! meaning that an `E^i` texel is `2^r` times as wide as an `E^j` texel, read from TOML:
//!
//! ```toml
//! root = "map"                     # the coarsest exemplar; root texels have unit diameter
//!
//! [[exemplar]]
//! name = "map"
//! image = "walnut"                 # an asset name, or a path relative to the TOML file
//!
//! [[exemplar]]
//! name = "grain"
//! image = "leather"
//!
//! [[edge]]
//! source = "map"
//! destination = "grain"
//! r = 2
//! ```
//!
//! Every exemplar has an implicit `r = 0` self-loop. Edges need `r < r_max = L − 3` (the
//! paper's rule, P:74), with `L` the smaller finest level of the two ends; every exemplar must
//! be reachable from the root. Errors name the file, the line and the field.

use crate::error::SynthError;
use crate::exemplar::Exemplar;
use serde::Deserialize;
use std::collections::VecDeque;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Most exemplars of one graph (the synthesis state keeps the exemplar in 8 bits and the
/// GPU's lookup table from (exemplar, level) to analysed level has 16 slots per exemplar).
pub const MAX_GRAPH_EXEMPLARS: usize = 16;

/// Largest exemplar side of a graph, below the 2D synthesizer's: the GPU atlas packs a
/// position and an exemplar's size in 8 bits per axis (`atlas.rs`). Larger images are refused
/// rather than resampled: the edges state scales in each exemplar's own texels, which a
/// resample would silently change.
pub const MAX_MULTISCALE_SIDE: u32 = 256;

/// `r_max = L − R_MAX_MARGIN`: edges need `r < r_max` (P:74, "r_max = L − 3 provided good
/// results"), so that source and destination stacks overlap over enough scales.
pub const R_MAX_MARGIN: u32 = 3;

/// One directed edge of the graph (exemplar indices).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct GraphEdge {
    /// Source exemplar.
    pub source: usize,
    /// Destination exemplar.
    pub destination: usize,
    /// Scale relation: a source texel is `2^r` destination texels wide.
    pub r: u32,
}

/// The shape of a graph: what admissibility and the superexemplar need (no images).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Topology {
    /// Finest stack level `L_i` of every exemplar.
    pub finest: Vec<u32>,
    /// The explicit edges (implicit `r = 0` self-loops not included), sorted, no repeats.
    pub edges: Vec<GraphEdge>,
    /// The root exemplar.
    pub root: usize,
}

impl Topology {
    /// A topology from its parts (edges sorted and deduplicated; explicit `r = 0` self-loops
    /// dropped, they are implicit).
    pub fn new(finest: Vec<u32>, edges: &[(usize, usize, u32)], root: usize) -> Topology {
        let mut edges: Vec<GraphEdge> = edges
            .iter()
            .filter(|&&(s, d, r)| !(s == d && r == 0))
            .map(|&(source, destination, r)| GraphEdge {
                source,
                destination,
                r,
            })
            .collect();
        edges.sort();
        edges.dedup();
        Topology {
            finest,
            edges,
            root,
        }
    }

    /// Number of exemplars.
    pub fn exemplars(&self) -> usize {
        self.finest.len()
    }

    /// `r_max` of an edge between exemplars `a` and `b`.
    pub fn r_max(&self, a: usize, b: usize) -> u32 {
        self.finest[a]
            .min(self.finest[b])
            .saturating_sub(R_MAX_MARGIN)
    }

    /// Exemplars not reachable from the root along edges.
    pub fn unreachable(&self) -> Vec<usize> {
        let mut seen = vec![false; self.exemplars()];
        let mut queue = VecDeque::from([self.root]);
        seen[self.root] = true;
        while let Some(i) = queue.pop_front() {
            for e in self.edges.iter().filter(|e| e.source == i) {
                if !seen[e.destination] {
                    seen[e.destination] = true;
                    queue.push_back(e.destination);
                }
            }
        }
        (0..self.exemplars()).filter(|&i| !seen[i]).collect()
    }
}

/// A parsed graph file, its exemplars loaded.
#[derive(Clone, Debug)]
pub struct ExemplarGraph {
    /// The TOML file.
    pub file: PathBuf,
    /// Exemplar names, in file order (the index is the exemplar's number).
    pub names: Vec<String>,
    /// The exemplars, in the same order.
    pub exemplars: Vec<Exemplar>,
    /// Edges, finest levels and root.
    pub topology: Topology,
}

/// Why a graph file could not be used.
#[derive(Debug, thiserror::Error)]
pub enum GraphError {
    /// The file could not be read.
    #[error("{file}: cannot read the exemplar graph: {source}")]
    Io {
        /// The graph file.
        file: PathBuf,
        /// The system error.
        source: std::io::Error,
    },
    /// The file is not valid TOML or does not have the graph's shape.
    #[error("{file}:{line}: {problem}")]
    Syntax {
        /// The graph file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        problem: String,
    },
    /// A field has a value the graph cannot use.
    #[error("{file}:{line}: {field}: {problem}")]
    Invalid {
        /// The graph file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// The field (`edge #2.r`, `exemplar "grain".image`, `root`).
        field: String,
        /// What is wrong.
        problem: String,
    },
    /// An exemplar image could not be loaded.
    #[error("{file}:{line}: {field}: {source}")]
    Exemplar {
        /// The graph file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// The field.
        field: String,
        /// The loader's error.
        source: Box<SynthError>,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGraph {
    root: Spanned<String>,
    exemplar: Vec<Spanned<RawExemplar>>,
    #[serde(default)]
    edge: Vec<Spanned<RawEdge>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawExemplar {
    name: Spanned<String>,
    image: Spanned<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEdge {
    source: Spanned<String>,
    destination: Spanned<String>,
    r: Spanned<i64>,
}

struct Doc<'a> {
    file: &'a Path,
    text: &'a str,
}

impl Doc<'_> {
    fn line(&self, span: &Range<usize>) -> usize {
        let end = span.start.min(self.text.len());
        1 + self.text.as_bytes()[..end]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
    }

    fn invalid(&self, span: &Range<usize>, field: String, problem: String) -> GraphError {
        GraphError::Invalid {
            file: self.file.to_path_buf(),
            line: self.line(span),
            field,
            problem,
        }
    }
}

impl ExemplarGraph {
    /// Reads the graph file `file`; `resolve` turns an `image` value into a path (asset names,
    /// paths relative to the graph's folder: that is the caller's rule).
    ///
    /// # Errors
    /// [`GraphError`] naming the file, line and field.
    pub fn load(
        file: &Path,
        resolve: &dyn Fn(&str) -> Result<PathBuf, String>,
    ) -> Result<ExemplarGraph, GraphError> {
        let text = std::fs::read_to_string(file).map_err(|source| GraphError::Io {
            file: file.to_path_buf(),
            source,
        })?;
        Self::parse(file, &text, &|value| {
            let path = resolve(value)?;
            Exemplar::load(&path).map_err(|e| e.to_string())
        })
    }

    /// Parses graph text; `load` turns an `image` value into its exemplar.
    ///
    /// # Errors
    /// [`GraphError`] naming the file, line and field.
    pub fn parse(
        file: &Path,
        text: &str,
        load: &dyn Fn(&str) -> Result<Exemplar, String>,
    ) -> Result<ExemplarGraph, GraphError> {
        let doc = Doc { file, text };
        let raw: RawGraph = toml::from_str(text).map_err(|e| GraphError::Syntax {
            file: file.to_path_buf(),
            line: doc.line(&e.span().unwrap_or(0..0)),
            problem: e.message().trim_end().to_string(),
        })?;
        if raw.exemplar.is_empty() {
            return Err(doc.invalid(
                &(0..0),
                "exemplar".into(),
                "the graph has no [[exemplar]]".into(),
            ));
        }
        if raw.exemplar.len() > MAX_GRAPH_EXEMPLARS {
            return Err(doc.invalid(
                &raw.exemplar[MAX_GRAPH_EXEMPLARS].span(),
                "exemplar".into(),
                format!("a graph has at most {MAX_GRAPH_EXEMPLARS} exemplars"),
            ));
        }
        let mut names: Vec<String> = Vec::new();
        for (i, e) in raw.exemplar.iter().enumerate() {
            let name = e.get_ref().name.get_ref();
            if names.contains(name) {
                return Err(doc.invalid(
                    &e.get_ref().name.span(),
                    format!("exemplar #{}.name", i + 1),
                    format!("{name:?} is already the name of another exemplar"),
                ));
            }
            names.push(name.clone());
        }
        let find = |name: &Spanned<String>, field: String| {
            names
                .iter()
                .position(|n| n == name.get_ref())
                .ok_or_else(|| {
                    doc.invalid(
                        &name.span(),
                        field,
                        format!(
                            "no exemplar is named {:?} (known: {})",
                            name.get_ref(),
                            names.join(", ")
                        ),
                    )
                })
        };
        let root = find(&raw.root, "root".into())?;
        let mut edges = Vec::new();
        for (n, e) in raw.edge.iter().enumerate() {
            let e = e.get_ref();
            let label = format!("edge #{}", n + 1);
            let s = find(&e.source, format!("{label}.source"))?;
            let d = find(&e.destination, format!("{label}.destination"))?;
            edges.push((s, d, e.r.clone(), label));
        }
        let mut exemplars = Vec::new();
        for e in &raw.exemplar {
            let e = e.get_ref();
            let field = || format!("exemplar {:?}.image", e.name.get_ref());
            let exemplar = load(e.image.get_ref())
                .map_err(|problem| doc.invalid(&e.image.span(), field(), problem))?;
            if exemplar.width.max(exemplar.height) > MAX_MULTISCALE_SIDE {
                return Err(doc.invalid(
                    &e.image.span(),
                    field(),
                    format!(
                        "{} is {}x{}; multiscale exemplars are at most {MAX_MULTISCALE_SIDE} \
                         pixels a side (the atlas packs positions in 8 bits; resampling would \
                         change the scales the edges state, so scale it down yourself and \
                         adjust r)",
                        exemplar.source.display(),
                        exemplar.width,
                        exemplar.height
                    ),
                ));
            }
            exemplars.push(exemplar);
        }
        let finest: Vec<u32> = exemplars.iter().map(Exemplar::finest_level).collect();
        let probe = Topology::new(finest.clone(), &[], root);
        let mut plain = Vec::new();
        for (s, d, r, label) in &edges {
            let r_max = probe.r_max(*s, *d);
            let value = *r.get_ref();
            if value < 0 || value >= r_max as i64 {
                return Err(doc.invalid(
                    &r.span(),
                    format!("{label}.r"),
                    format!(
                        "r = {value}; it must lie in 0..{r_max} (r_max = L − {R_MAX_MARGIN}, L = {} the \
                         finest level of the smaller of {:?} and {:?})",
                        finest[*s].min(finest[*d]),
                        names[*s],
                        names[*d]
                    ),
                ));
            }
            plain.push((*s, *d, value as u32));
        }
        let topology = Topology::new(finest, &plain, root);
        if let Some(&lost) = topology.unreachable().first() {
            return Err(doc.invalid(
                &raw.exemplar[lost].get_ref().name.span(),
                format!("exemplar {:?}", names[lost]),
                format!(
                    "not reachable from the root {:?} along the edges",
                    names[root]
                ),
            ));
        }
        Ok(ExemplarGraph {
            file: file.to_path_buf(),
            names,
            exemplars,
            topology,
        })
    }
}
