//! The parts of the lazy correction's per-voxel decision, for a profile that times them one
//! by one (`lazysolid bench lazy --profile-correction`): each part is the kernel compiled to stop
//! after it (a specialization constant of `lazy_correct.comp`, `SOLID_PARTS_*` in
//! `glsl/include/synth/solid_correct.glsl`), so the difference between two parts' device times
//! is what the later part costs. Every part short of [`CorrectParts::All`] stores the current
//! triple as the new version: a state profiled with one gives wrong colours.

/// How much of the correction runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CorrectParts {
    /// Look up the 18 plane neighbours and read their versions.
    Neighbours = 1,
    /// Also sum the predicted exemplar neighbourhoods of the three planes.
    Sums = 2,
    /// Also gather each role's candidate sets and compute each set's own-role distance.
    OwnDistances = 3,
    /// Also evaluate every candidate and choose: the synthesizer.
    All = 4,
}

impl CorrectParts {
    /// Every part, cumulative, in the order a profile runs them.
    pub const PROFILE: [CorrectParts; 4] = [
        CorrectParts::Neighbours,
        CorrectParts::Sums,
        CorrectParts::OwnDistances,
        CorrectParts::All,
    ];

    /// What the part adds, as a profile row names it.
    pub fn name(self) -> &'static str {
        match self {
            CorrectParts::Neighbours => "neighbour lookups and reads",
            CorrectParts::Sums => "neighbourhood sums",
            CorrectParts::OwnDistances => "candidate sets and own-role distances",
            CorrectParts::All => "candidate distances and choice",
        }
    }

    /// The value of the kernel's specialization constant.
    pub(crate) fn constant(self) -> u32 {
        self as u32
    }
}
