//! The new surface a broken mesh's store grows by: the cap faces of its pieces.

use crate::scene::Scene;
use glam::Vec3;

/// The cap faces of every piece cut from mesh `root` that an instance shows with `material`, as
/// one triangle list (each piece's vertices appended), or `None` when nothing was cut from it.
pub(crate) fn caps_of(
    scene: &Scene,
    root: usize,
    material: usize,
) -> Option<(Vec<Vec3>, Vec<[u32; 3]>)> {
    let mut pieces: Vec<usize> = scene
        .instances
        .iter()
        .filter(|i| i.material == material)
        .map(|i| i.mesh)
        .filter(|&m| matches!(&scene.meshes[m].cut_from, Some((r, _)) if *r == root))
        .collect();
    pieces.sort_unstable();
    pieces.dedup();
    if pieces.is_empty() {
        return None;
    }
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for m in pieces {
        let (mesh, flags) = (&scene.meshes[m].mesh, &scene.meshes[m].cut_from.as_ref()?.1);
        let base = positions.len() as u32;
        positions.extend_from_slice(&mesh.positions);
        triangles.extend(
            mesh.triangles
                .iter()
                .zip(flags)
                .filter(|(_, &cap)| cap)
                .map(|(t, _)| t.map(|v| v + base)),
        );
    }
    Some((positions, triangles))
}
