#!/usr/bin/env python3
"""Writes the assets of scenes/glints.toml (pure Python, deterministic):

- scenes/glints/scratches.png: a 256x256 16-bit height map of straight scratches of random
  direction, depth and width over a faint isotropic bump field, wrapped at the edges
  (scratched metal; read with height_map and height_scale);
- scenes/glints/bent_quad.obj: a 2 x 2 quad in the object x-z plane bent about the z axis
  into a quarter cylinder arc of small curvature (y = 0.25 x^2), 32 x 8 cells.
"""
import math, os, random, struct, zlib

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "glints")
N = 256


def heights():
    r = random.Random(4)
    h = [0.0] * (N * N)
    def wrap(d):
        return d - N * round(d / N)
    # Faint bumps.
    for _ in range(300):
        cx, cy = r.random() * N, r.random() * N
        rad, amp = 1.0 + 2.5 * r.random(), (r.random() * 2 - 1) * 0.15
        R = int(3 * rad) + 1
        for dy in range(-R, R + 1):
            for dx in range(-R, R + 1):
                x, y = int(cx) + dx, int(cy) + dy
                ddx, ddy = wrap(x - cx), wrap(y - cy)
                h[(y % N) * N + x % N] += amp * math.exp(-(ddx * ddx + ddy * ddy) / (2 * rad * rad))
    # Scratches: segments of random length and direction, a Gaussian groove across.
    for _ in range(160):
        cx, cy = r.random() * N, r.random() * N
        a = r.random() * math.pi
        length = 20 + r.random() * 200
        depth, width = 0.4 + r.random() * 1.2, 0.6 + r.random() * 0.9
        ux, uy = math.cos(a), math.sin(a)
        steps = int(length)
        for t in range(-steps // 2, steps // 2):
            px, py = cx + ux * t, cy + uy * t
            for o in range(-3, 4):
                x, y = int(round(px - uy * o)), int(round(py + ux * o))
                # distance of the texel to the line
                d = abs(wrap(x - cx) * -uy + wrap(y - cy) * ux)
                i = (y % N) * N + x % N
                h[i] = min(h[i], -depth * math.exp(-d * d / (2 * width * width))) if d < 3.5 else h[i]
    lo, hi = min(h), max(h)
    return [(v - lo) / (hi - lo) for v in h]


def write_png16(path, w, hgt, values):
    raw = b"".join(b"\x00" + b"".join(struct.pack(">H", int(round(v * 65535))) for v in values[y * w:(y + 1) * w]) for y in range(hgt))
    def chunk(t, d):
        c = struct.pack(">I", len(d)) + t + d
        return c + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, hgt, 16, 0, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    open(path, "wb").write(png)


def write_bent_quad(path, nx=32, nz=8):
    lines = ["# A 2 x 2 quad in the x-z plane bent about z: y = 0.25 x^2, x in [-1, 1]."]
    for j in range(nz + 1):
        for i in range(nx + 1):
            x = -1 + 2 * i / nx
            z = -1 + 2 * j / nz
            lines.append(f"v {x:.6f} {0.25 * x * x:.6f} {z:.6f}")
    for j in range(nz):
        for i in range(nx):
            a = j * (nx + 1) + i + 1
            b, c, d = a + 1, a + nx + 2, a + nx + 1
            lines.append(f"f {a} {d} {c}")
            lines.append(f"f {a} {c} {b}")
    open(path, "w").write("\n".join(lines) + "\n")


if __name__ == "__main__":
    os.makedirs(ROOT, exist_ok=True)
    write_png16(os.path.join(ROOT, "scratches.png"), N, N, heights())
    write_bent_quad(os.path.join(ROOT, "bent_quad.obj"))
