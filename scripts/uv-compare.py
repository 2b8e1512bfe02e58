# Compares the export's charts (uvunwrap) with xatlas' on the same pieces: charts, atlas use,
# area and angle distortion (area-weighted over the surface), xatlas at the export's texel
# density and padding on the pieces' welded geometry. docs/fracture.md, "Export", has the
# figures. Needs the `xatlas` Python bindings:
#   python3 -m venv /tmp/xa && /tmp/xa/bin/pip install xatlas numpy
#   /tmp/xa/bin/python scripts/uv-compare.py EXPORT/armadillo 8   # folder of piece_*.obj, padding
import glob, struct, sys, time
import numpy as np
import xatlas

def read_obj(path):
    v, vt, f = [], [], []
    for line in open(path):
        s = line.split()
        if not s: continue
        if s[0] == 'v': v.append([float(x) for x in s[1:4]])
        elif s[0] == 'vt': vt.append([float(s[1]), 1.0 - float(s[2])])
        elif s[0] == 'f': f.append([int(c.split('/')[0]) - 1 for c in s[1:4]])
    return np.array(v), np.array(vt), np.array(f)

def png_size(path):
    d = open(path, 'rb').read(24); return struct.unpack('>II', d[16:24])

def metrics(P, UV, F, W, H):
    a, b, c = P[F[:,0]], P[F[:,1]], P[F[:,2]]
    e1, e2 = b - a, c - a
    n = np.cross(e1, e2); A3 = 0.5 * np.linalg.norm(n, axis=1)
    ua, ub, uc = UV[F[:,0]]*[W,H], UV[F[:,1]]*[W,H], UV[F[:,2]]*[W,H]
    f1, f2 = ub - ua, uc - ua
    Auv = 0.5 * np.abs(f1[:,0]*f2[:,1] - f1[:,1]*f2[:,0])
    ok = (A3 > 1e-14) & (Auv > 1e-12)
    # Jacobian from a local 2D frame of the triangle to UV.
    x = e1 / np.linalg.norm(e1, axis=1)[:,None]
    y = np.cross(n / (2*A3[:,None] + 1e-30), x)
    p1 = np.stack([np.sum(e1*x,1), np.sum(e1*y,1)], 1)
    p2 = np.stack([np.sum(e2*x,1), np.sum(e2*y,1)], 1)
    ratio_angle = []
    for i in np.nonzero(ok)[0]:
        M = np.array([p1[i], p2[i]]).T; U = np.array([f1[i], f2[i]]).T
        J = U @ np.linalg.inv(M)
        s = np.linalg.svd(J, compute_uv=False); ratio_angle.append(s[0]/s[1])
    w = A3[ok] / A3[ok].sum()
    r = (Auv[ok]/Auv[ok].sum()) / (A3[ok]/A3[ok].sum())
    area = np.sum(w * np.maximum(r, 1/r))
    angle = np.sum(w * np.array(ratio_angle))
    return Auv[ok].sum(), area, angle, A3[ok].sum()

def charts_of(F, n):
    parent = list(range(n))
    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]; i = parent[i]
        return i
    for t in F:
        for k in (1, 2):
            ra, rb = find(t[0]), find(t[k])
            if ra != rb: parent[ra] = rb
    return len({find(t[0]) for t in F})

rows = {'uvunwrap': [0,0,0,0,0,0,0], 'xatlas': [0,0,0,0,0,0,0]}
for obj in sorted(glob.glob(sys.argv[1] + '/piece_*.obj')):
    P, UV, F = read_obj(obj)
    W, H = png_size(obj[:-4] + '.png')
    used, area, angle, A3 = metrics(P, UV, F, W, H)
    density = np.sqrt(used / A3)
    r = rows['uvunwrap']; r[0] += charts_of(F, len(P)); r[1] += used; r[2] += W*H; r[3] += area*A3; r[4] += angle*A3; r[5] += A3
    # xatlas on the welded geometry, at the same texel density and padding.
    key = {tuple(p): i for i, p in enumerate(P)}
    idx = {i: key[tuple(p)] for i, p in enumerate(P)}
    uniq = sorted(set(idx.values())); remap = {u: j for j, u in enumerate(uniq)}
    V = P[uniq].astype(np.float32); G = np.array([[remap[idx[i]] for i in t] for t in F], dtype=np.uint32)
    atlas = xatlas.Atlas(); atlas.add_mesh(V, G)
    po = xatlas.PackOptions(); po.texels_per_unit = float(density); po.padding = int(sys.argv[2]); po.bilinear = True
    t0 = time.time(); atlas.generate(xatlas.ChartOptions(), po); dt = time.time() - t0
    vmap, Fx, UVx = atlas[0]
    Px = V[vmap]
    usedx, areax, anglex, A3x = metrics(Px.astype(np.float64), UVx.astype(np.float64), Fx, atlas.width, atlas.height)
    r = rows['xatlas']; r[0] += atlas.chart_count; r[1] += usedx; r[2] += atlas.width*atlas.height; r[3] += areax*A3x; r[4] += anglex*A3x; r[5] += A3x; r[6] += dt
for name, r in rows.items():
    print(f"{name:9s} charts {r[0]:5d}  chart texels / atlas texels {r[1]/r[2]:.3f}  atlas texels {r[2]:8d}  area distortion {r[3]/r[5]:.4f}  angle distortion {r[4]/r[5]:.4f}" + (f"  time {r[6]:.2f} s" if r[6] else ""))
