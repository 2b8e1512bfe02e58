//! `lazysolid fracture`: cut a closed mesh by planes or break it into Voronoi pieces, and write
//! every piece as OBJ with its cut faces in their own group and material, ready for other
//! tools (and for the scenes' `[fracture]`, which makes the same pieces).

use super::assets;
use super::output::check_writable_dir;
use super::GlobalArgs;
use anyhow::{bail, Context};
use clap::Args;
use glam::{DVec3, Vec3};
use lazysolid_renderer::export::{export_broken, ExportOptions};
use lazysolid_renderer::fracture::{
    check_closed, cut_pieces, fracture, random_sites, volume, write_fragment_obj,
    write_material_library, Fragment, Plane, MAX_PIECES,
};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::Scene;
use std::path::{Path, PathBuf};
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
    /// Also export the pieces with their matter, synthesized lazily from this exemplar (a name
    /// in the assets' exemplars or an image path): `<mesh>.glb` and `<mesh>/piece_NNN.obj` +
    /// `.mtl` + `.png` in --out-dir, as `render --export` writes them (docs/fracture.md,
    /// "Export"), in the mesh's coordinates.
    #[arg(long, value_name = "EXEMPLAR")]
    pub matter: Option<String>,
    /// Resolution of the matter's store (voxels along the mesh's longest side).
    #[arg(long, value_name = "R", default_value_t = 128, requires = "matter")]
    pub matter_res: u32,
    /// Seed of the matter's synthesis.
    #[arg(long, value_name = "SEED", default_value_t = 1, requires = "matter")]
    pub matter_seed: u32,
    /// Texel density of the atlases, texels per unit of the mesh's longest side (default:
    /// --matter-res, one texel per voxel).
    #[arg(long, value_name = "TEXELS", requires = "matter")]
    pub export_density: Option<f32>,
    /// Mip levels the atlases must not bleed through (charts padded by 2^K texels).
    #[arg(long, value_name = "K", default_value_t = 3, requires = "matter")]
    pub export_mips: u32,
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

pub fn run(args: &FractureArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    let path = assets::mesh("MESH", &args.mesh)?;
    check_writable_dir("--out-dir", &args.out_dir)?;
    let mesh = Mesh::load(&path).with_context(|| format!("MESH {}", args.mesh))?;
    check_closed(&mesh)?;
    let start = Instant::now();
    let mut sites = Vec::new();
    let pieces = match (args.pieces, args.plane.is_empty()) {
        (Some(n), _) => {
            if n == 0 || n > MAX_PIECES {
                bail!("--pieces {n}: a fracture makes 1 to {MAX_PIECES} pieces");
            }
            sites = random_sites(&mesh, n, args.seed)?;
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
    if let Some(exemplar) = &args.matter {
        export_matter(args, global, &path, &mesh, &sites, exemplar)?;
    }
    Ok(())
}

/// `--matter`: the same break as a scene — the mesh in its unit cube (where lazysolid's
/// stores live) carved out of matter synthesized from `exemplar`, placed back at its own
/// coordinates by the instance's transform, broken by the same sites or planes mapped into
/// the unit cube — whose stores are baked and exported with the pieces.
fn export_matter(
    args: &FractureArgs,
    global: &GlobalArgs,
    path: &Path,
    mesh: &Mesh,
    sites: &[Vec3],
    exemplar: &str,
) -> anyhow::Result<()> {
    let mut unit = mesh.clone();
    let (scale, offset) = unit.normalize_to_unit_cube();
    let min = mesh.bounds().min;
    let to_unit = |p: Vec3| (p - min) * scale + offset;
    let list = |p: Vec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
    let translate = min - offset / scale;
    let abs = std::fs::canonicalize(path).with_context(|| format!("MESH {}", path.display()))?;
    let mut text = format!(
        "[camera]\nposition = [2.0, 2.0, 2.0]\nlook_at = [0.5, 0.5, 0.5]\nfov_y = 40\n\
         [render]\nwidth = 8\nheight = 8\nspp = 1\n\
         [[mesh]]\nname = {name:?}\npath = {mesh:?}\n\
         [[material]]\nname = \"matter\"\nkind = \"lambertian\"\n\
         texture = {{ kind = \"synthesized\", exemplar = {exemplar:?}, seed = {seed}, resolution = {res}, store = \"coherent_hash\" }}\n\
         [[instance]]\nname = {name:?}\nmesh = {name:?}\nmaterial = \"matter\"\nscale = {s}\ntranslate = {t}\n",
        name = args.mesh_name(),
        mesh = abs.display().to_string(),
        seed = args.matter_seed,
        res = args.matter_res,
        s = 1.0 / scale,
        t = list(translate),
    );
    for &[x, y, z, d] in &args.plane {
        let n = DVec3::new(x, y, z);
        let on = (n * (d / n.length_squared())).as_vec3();
        text += &format!(
            "[[cut]]\ninstance = {:?}\npoint = {}\nnormal = [{x}, {y}, {z}]\n",
            args.mesh_name(),
            list(to_unit(on))
        );
    }
    if !sites.is_empty() {
        let sites: Vec<String> = sites.iter().map(|&p| list(to_unit(p))).collect();
        text += &format!(
            "[[fracture]]\ninstance = {:?}\nsites = [{}]\n",
            args.mesh_name(),
            sites.join(", ")
        );
    }
    let source = std::env::current_dir()?.join("fracture --matter");
    let scene = Scene::parse(&text, &source).context("--matter: the scene of the export")?;
    let gpu = global.gpu()?;
    let start = Instant::now();
    let tracer = PathTracer::new(&gpu, &scene).context("--matter: baking the matter")?;
    let baked = start.elapsed().as_secs_f64();
    let options = ExportOptions {
        texels_per_unit: args.export_density,
        mip_levels: args.export_mips,
    };
    let objects = export_broken(&scene, tracer.scene_stores(), &args.out_dir, &options)?;
    for o in &objects {
        let (texels, holes) = (o.covered(), o.holes());
        println!(
            "matter: {exemplar} at R = {} baked in {baked:.1} s; wrote {} ({} pieces, {} texels per unit, padding {} texels, {texels} texels of matter{}) and {}/piece_*.obj + .mtl + .png",
            args.matter_res,
            o.glb.display(),
            o.pieces.len(),
            o.texels_per_unit,
            o.padding,
            if holes > 0 { format!(", {holes} with none stored") } else { String::new() },
            args.out_dir.join(&o.name).display()
        );
    }
    Ok(())
}

impl FractureArgs {
    /// The mesh's name for the export's files: the asset name, or the file's stem.
    fn mesh_name(&self) -> String {
        Path::new(&self.mesh)
            .file_stem()
            .map_or_else(|| self.mesh.clone(), |s| s.to_string_lossy().into_owned())
    }
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
