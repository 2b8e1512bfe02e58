//! The figures of thesis Table 4.1 (armadillo, equivalent resolution 1024³, viewpoint of
//! Fig. 4.8) and of §4.2.2 for nearest sampling, which the benchmark prints beside its own.
//! Frame rates are only comparable as ratios within one setup: Table 4.1 for the trilinear rows,
//! the §4.2.2 measurement (GeForce 7800 GTX, 800² window) for the nearest rows.

/// A structure as the thesis names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ThesisRow {
    /// Octree texture, nearest: 18.0 MB, 180 fps (§4.2.2).
    OctreeNearest,
    /// Perfect spatial hash, nearest: 7.5 MB, 370 fps (§4.2.2).
    HashNearest,
    /// Octree texture, 8 lookups for trilinear: 32.6 MB, 25 FPS (Table 4.1).
    OctreeTrilinear,
    /// Hashed texture, 8 lookups for trilinear: 15.7 MB, 34 FPS (Table 4.1).
    HashTrilinear,
    /// Hashed texture, blocking for trilinear: 45.9 MB, 135 FPS (Table 4.1).
    HashBlocked,
    /// TileTree: 11.4 MB, 91 FPS (Table 4.1).
    TileTree,
}

impl ThesisRow {
    /// Megabytes (10^6 bytes) the thesis reports.
    pub fn megabytes(self) -> f64 {
        match self {
            ThesisRow::OctreeNearest => 18.0,
            ThesisRow::HashNearest => 7.5,
            ThesisRow::OctreeTrilinear => 32.6,
            ThesisRow::HashTrilinear => 15.7,
            ThesisRow::HashBlocked => 45.9,
            ThesisRow::TileTree => 11.4,
        }
    }

    /// Frames per second the thesis reports.
    pub fn fps(self) -> f64 {
        match self {
            ThesisRow::OctreeNearest => 180.0,
            ThesisRow::HashNearest => 370.0,
            ThesisRow::OctreeTrilinear => 25.0,
            ThesisRow::HashTrilinear => 34.0,
            ThesisRow::HashBlocked => 135.0,
            ThesisRow::TileTree => 91.0,
        }
    }

    /// The row of the same setup that frame rates are divided by: the octree of the same
    /// filtering.
    pub fn baseline(self) -> ThesisRow {
        match self {
            ThesisRow::OctreeNearest | ThesisRow::HashNearest => ThesisRow::OctreeNearest,
            _ => ThesisRow::OctreeTrilinear,
        }
    }

    /// Speed relative to [`ThesisRow::baseline`] in the thesis.
    pub fn speedup(self) -> f64 {
        self.fps() / self.baseline().fps()
    }

    /// How the thesis labels the row.
    pub fn label(self) -> &'static str {
        match self {
            ThesisRow::OctreeNearest => "octree texture, nearest (§4.2.2)",
            ThesisRow::HashNearest => "perfect spatial hash, nearest (§4.2.2)",
            ThesisRow::OctreeTrilinear => "octree texture, 8 lookups (Table 4.1)",
            ThesisRow::HashTrilinear => "hashed texture, 8 lookups (Table 4.1)",
            ThesisRow::HashBlocked => "hashed texture, blocking (Table 4.1)",
            ThesisRow::TileTree => "TileTree (Table 4.1)",
        }
    }
}
