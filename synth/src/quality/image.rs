//! A float RGB image in [0, 1] and what the quality figures need of it: crops, a Gaussian
//! pyramid and luminance.

/// Row-major RGB in [0, 1].
#[derive(Clone, Debug)]
pub struct LinearImage {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row-major pixels.
    pub pixels: Vec<[f32; 3]>,
}

/// The binomial kernel of the pyramid (a Gaussian of σ ≈ 1): enough to keep the next octave
/// free of aliasing without washing out what is left of the structures.
const BINOMIAL: [f32; 5] = [1.0 / 16.0, 4.0 / 16.0, 6.0 / 16.0, 4.0 / 16.0, 1.0 / 16.0];

impl LinearImage {
    /// An 8-bit RGB image of `width`×`height`.
    ///
    /// # Panics
    /// When `rgb` does not hold `width * height` pixels (a caller's bug).
    pub fn from_rgb8(rgb: &[[u8; 3]], width: usize, height: usize) -> LinearImage {
        assert_eq!(
            rgb.len(),
            width * height,
            "pixel count of a {width}x{height} image"
        );
        LinearImage {
            width,
            height,
            pixels: rgb
                .iter()
                .map(|p| p.map(|c| f32::from(c) / 255.0))
                .collect(),
        }
    }

    /// The pixel at (x, y).
    pub fn at(&self, x: usize, y: usize) -> [f32; 3] {
        self.pixels[y * self.width + x]
    }

    /// The `w`×`h` crop whose top-left pixel is (x0, y0).
    ///
    /// # Panics
    /// When the crop leaves the image (a caller's bug).
    pub fn crop(&self, x0: usize, y0: usize, w: usize, h: usize) -> LinearImage {
        assert!(
            x0 + w <= self.width && y0 + h <= self.height,
            "crop inside the image"
        );
        LinearImage {
            width: w,
            height: h,
            pixels: (y0..y0 + h)
                .flat_map(|y| (x0..x0 + w).map(move |x| (x, y)))
                .map(|(x, y)| self.at(x, y))
                .collect(),
        }
    }

    /// The next octave: blurred by the binomial kernel (edges clamped) and halved.
    pub fn half(&self) -> LinearImage {
        let (w, h) = (self.width, self.height);
        let clamp = |v: isize, n: usize| v.clamp(0, n as isize - 1) as usize;
        let blur_x: Vec<[f32; 3]> = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as isize, i / w);
                let mut acc = [0.0f32; 3];
                for (k, wk) in BINOMIAL.iter().enumerate() {
                    let p = self.at(clamp(x + k as isize - 2, w), y);
                    (0..3).for_each(|c| acc[c] += wk * p[c]);
                }
                acc
            })
            .collect();
        let (hw, hh) = ((w / 2).max(1), (h / 2).max(1));
        let pixels = (0..hw * hh)
            .map(|i| {
                let (x, y) = ((i % hw) * 2, ((i / hw) * 2) as isize);
                let mut acc = [0.0f32; 3];
                for (k, wk) in BINOMIAL.iter().enumerate() {
                    let p = blur_x[clamp(y + k as isize - 2, h) * w + x.min(w - 1)];
                    (0..3).for_each(|c| acc[c] += wk * p[c]);
                }
                acc
            })
            .collect();
        LinearImage {
            width: hw,
            height: hh,
            pixels,
        }
    }

    /// Octave `self` minus the expansion of its next octave `coarse` (bilinear, coarse pixel
    /// `i` sitting at fine pixel `2i`, as [`LinearImage::half`] samples): the detail the next
    /// octave does not hold.
    pub fn minus_expanded(&self, coarse: &LinearImage) -> LinearImage {
        let sample = |x: usize, cn: usize| {
            let (i, f) = (x / 2, (x % 2) as f32 * 0.5);
            (i.min(cn - 1), (i + 1).min(cn - 1), f)
        };
        let pixels = (0..self.width * self.height)
            .map(|k| {
                let (x, y) = (k % self.width, k / self.width);
                let (x0, x1, fx) = sample(x, coarse.width);
                let (y0, y1, fy) = sample(y, coarse.height);
                let p = self.pixels[k];
                std::array::from_fn(|c| {
                    let top = coarse.at(x0, y0)[c] * (1.0 - fx) + coarse.at(x1, y0)[c] * fx;
                    let bottom = coarse.at(x0, y1)[c] * (1.0 - fx) + coarse.at(x1, y1)[c] * fx;
                    p[c] - (top * (1.0 - fy) + bottom * fy)
                })
            })
            .collect();
        LinearImage {
            width: self.width,
            height: self.height,
            pixels,
        }
    }

    /// The Laplacian pyramid of `octaves` bands: each Gaussian octave minus the expansion of
    /// the next, finest first, and the coarsest Gaussian octave itself last (colour and the
    /// largest structures).
    pub fn laplacian(&self, octaves: usize) -> Vec<LinearImage> {
        let gauss = self.pyramid(octaves);
        (0..gauss.len())
            .map(|o| match gauss.get(o + 1) {
                Some(next) => gauss[o].minus_expanded(next),
                None => gauss[o].clone(),
            })
            .collect()
    }

    /// The image and its next `octaves - 1` octaves.
    pub fn pyramid(&self, octaves: usize) -> Vec<LinearImage> {
        let mut out = vec![self.clone()];
        while out.len() < octaves {
            let next = out.last().expect("one octave").half();
            out.push(next);
        }
        out
    }

    /// Rec. 709 luminance per pixel.
    pub fn luminance(&self) -> Vec<f32> {
        self.pixels
            .iter()
            .map(|p| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2])
            .collect()
    }
}
