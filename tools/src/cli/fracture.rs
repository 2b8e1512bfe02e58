//! `lazysolid fracture`: cut a closed mesh by planes or break it into Voronoi pieces, and write
//! every piece as OBJ with its cut faces in their own group and material, ready for other
//! tools (and for the scenes' `[fracture]`, which makes the same pieces).

use super::assets;
use super::output::check_writable_dir;
use anyhow::{bail, Context};
use clap::Args;
use glam::DVec3;
use lazysolid_renderer::fracture::{
    check_closed, cut_pieces, fracture, random_sites, volume, write_fragment_obj,
    write_material_library, Fragment, Plane, MAX_PIECES,
};
use lazysolid_renderer::mesh::Mesh;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Args, Debug)]
pub struct FractureArgs {
    /// The mesh: a name in the assets' meshes (armadillo, bunny00, ...) or a path to an OFF or
    /// OBJ file. It must be closed (every edge shared by two triangles); pieces keep its
    /// coordinates.
    pub mesh: String,
    /// Voronoi pieces: sites drawn uniformly inside the mesh from --seed.
    #[arg(long, conflicts_with = "plane")]
    pub pieces: Option<usize>,
    /// Seed of the Voronoi sites: same seed, same pieces.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// A cutting plane `nx,ny,nz,d` (the points with n·x = d, in the mesh's coordinates);
    /// repeat it to cut every piece made so far again. A plane that misses a piece leaves it
    /// whole and is reported.
    #[arg(long, value_parser = parse_plane, allow_hyphen_values = true)]
    pub plane: Vec<[f64; 4]>,
    /// Folder for `piece_NNN.obj` and `fragments.mtl` (created if needed).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
}

fn parse_plane(value: &str) -> Result<[f64; 4], String> {
    let v: Vec<f64> = value
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{value:?}: {e} (expected nx,ny,nz,d)"))?;
    match v[..] {
        [x, y, z, d]
            if [x, y, z, d].iter().all(|c| c.is_finite()) && (x, y, z) != (0.0, 0.0, 0.0) =>
        {
            Ok([x, y, z, d])
        }
        _ => Err(format!(
            "{value:?}: expected four finite numbers nx,ny,nz,d with a non-zero normal"
        )),
    }
}

pub fn run(args: &FractureArgs) -> anyhow::Result<()> {
    let path = assets::mesh("MESH", &args.mesh)?;
    check_writable_dir("--out-dir", &args.out_dir)?;
    let mesh = Mesh::load(&path).with_context(|| format!("MESH {}", args.mesh))?;
    check_closed(&mesh)?;
    let start = Instant::now();
    let pieces = match (args.pieces, args.plane.is_empty()) {
        (Some(n), _) => {
            if n == 0 || n > MAX_PIECES {
                bail!("--pieces {n}: a fracture makes 1 to {MAX_PIECES} pieces");
            }
            let sites = random_sites(&mesh, n, args.seed)?;
            fracture(&mesh, &sites)?
        }
        (None, false) => cut(&mesh, &args.plane)?,
        (None, true) => {
            bail!("give --pieces N (Voronoi fracture) or one or more --plane nx,ny,nz,d")
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    std::fs::create_dir_all(&args.out_dir)
        .with_context(|| format!("--out-dir {}: creating it", args.out_dir.display()))?;
    write_material_library(&args.out_dir.join("fragments.mtl"))?;
    let whole = volume(&mesh.positions, &mesh.triangles);
    let mut sum = 0.0;
    println!("piece  triangles  interior  volume share");
    for (i, piece) in pieces.iter().enumerate() {
        let name = format!("piece_{i:03}");
        write_fragment_obj(
            piece,
            &args.out_dir.join(format!("{name}.obj")),
            &name,
            Some("fragments.mtl"),
        )?;
        let v = piece.volume();
        sum += v;
        let caps = piece.interior.iter().filter(|&&f| f).count();
        println!(
            "{i:5}  {:9}  {caps:8}  {:11.4} %",
            piece.triangles.len(),
            100.0 * v / whole
        );
    }
    println!(
        "{} pieces of {} in {seconds:.2} s; their volumes sum to the mesh's within {:.1e} (relative)",
        pieces.len(),
        path.display(),
        ((sum - whole) / whole).abs()
    );
    let crossings: usize = pieces.iter().map(|p| p.resolved_crossings).sum();
    if crossings > 0 {
        println!(
            "the surface intersects itself: {crossings} crossing(s) of cut segments resolved in the pieces' caps \
             (counted per piece); the pieces are closed and intersect themselves where the mesh does"
        );
    }
    let copies: usize = pieces.iter().map(|p| p.separated_vertices).sum();
    let splits: usize = pieces.iter().map(|p| p.split_edges).sum();
    if copies + splits > 0 {
        println!(
            "sheets of the surface met at an edge or a vertex in some pieces: separated them with \
             {copies} vertex copies and {splits} edge splits, so every piece is a closed 2-manifold"
        );
    }
    println!(
        "wrote {}/piece_*.obj and fragments.mtl",
        args.out_dir.display()
    );
    Ok(())
}

/// Cuts the mesh by every plane in turn, each plane cutting every piece made so far.
fn cut(mesh: &Mesh, planes: &[[f64; 4]]) -> anyhow::Result<Vec<Fragment>> {
    let mut pieces = vec![Fragment::whole(mesh)];
    for (k, &[x, y, z, d]) in planes.iter().enumerate() {
        let plane = Plane::new(DVec3::new(x, y, z), d);
        let missed;
        (pieces, missed) = cut_pieces(pieces, plane, &mesh.source)?;
        if missed {
            println!(
                "--plane {x},{y},{z},{d} (plane {}) misses the mesh: nothing cut",
                k + 1
            );
        }
    }
    Ok(pieces)
}
