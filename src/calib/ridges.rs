//! Lane-marking pixels: narrow bright ridges along image rows.
//!
//! A marking crossing a row is brighter than the road on both sides, at a distance that grows
//! with the marking's width in pixels. The response at column x is the symmetric
//! local-threshold filter at the best of a few half-widths t:
//!
//! ```text
//! r(x) = max over t in SCALES of min(m(x) - m(x - t), m(x) - m(x + t))
//! ```
//!
//! which is zero on a step edge (one side is as bright) and positive only on a ridge. Pixels
//! with r >= `min_contrast` form runs along the row; each run gives one pixel, the middle of
//! its strongest responses: about one pixel per marking and row, at its centre.

use crate::image::Image;

/// Half-widths t tried, in working pixels (markings from 2 to about 20 pixels wide).
pub const SCALES: [usize; 4] = [2, 4, 7, 11];

/// A marking pixel: working-image column and row, and its ridge contrast.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RidgePixel {
    /// Column.
    pub x: u16,
    /// Row.
    pub y: u16,
    /// Ridge contrast r(x), grey levels.
    pub contrast: u8,
}

/// Appends the ridge pixels of rows `rows` of `img` to `out`; `scratch` holds one row's
/// responses.
pub fn find_ridges(
    img: &Image<u8>,
    rows: std::ops::Range<usize>,
    min_contrast: i32,
    scratch: &mut Vec<i32>,
    out: &mut Vec<RidgePixel>,
) {
    let w = img.width();
    let t_max = SCALES[SCALES.len() - 1];
    if w < 2 * t_max + 3 {
        return;
    }
    scratch.clear();
    scratch.resize(w, 0);
    for y in rows.start..rows.end.min(img.height()) {
        let row = img.row(y);
        for x in t_max..w - t_max {
            let c = row[x] as i32;
            let mut best = 0;
            for t in SCALES {
                let r = (c - row[x - t] as i32).min(c - row[x + t] as i32);
                best = best.max(r);
            }
            scratch[x] = best;
        }
        // One pixel per run of r >= min_contrast: the middle of the run's maxima (a wide
        // marking gives a plateau of equal responses).
        let mut x = t_max;
        while x < w - t_max {
            if scratch[x] < min_contrast {
                x += 1;
                continue;
            }
            let (mut best, mut first, mut last) = (scratch[x], x, x);
            while x < w - t_max && scratch[x] >= min_contrast {
                if scratch[x] > best {
                    (best, first, last) = (scratch[x], x, x);
                } else if scratch[x] == best {
                    last = x;
                }
                x += 1;
            }
            out.push(RidgePixel {
                x: ((first + last) / 2) as u16,
                y: y as u16,
                contrast: best.min(255) as u8,
            });
        }
    }
}

/// Keeps the pixels of `pixels` (in row order, as [`find_ridges`] writes them) that have a
/// neighbour in the row above or below within `max_dx` columns: paint runs along rows, while
/// texture (grass, gravel, foliage) gives isolated ridges.
pub fn keep_continuous(pixels: &mut Vec<RidgePixel>, max_dx: u16) {
    let n = pixels.len();
    // Start of each pixel's row and of the next row, by scanning once.
    let mut keep = vec![false; n];
    let mut row_start = 0;
    let mut prev_start = 0;
    let mut prev_row = None::<u16>;
    while row_start < n {
        let y = pixels[row_start].y;
        let mut row_end = row_start;
        while row_end < n && pixels[row_end].y == y {
            row_end += 1;
        }
        if prev_row == Some(y.wrapping_sub(1)) {
            for i in row_start..row_end {
                for j in prev_start..row_start {
                    if pixels[i].x.abs_diff(pixels[j].x) <= max_dx {
                        keep[i] = true;
                        keep[j] = true;
                    }
                }
            }
        }
        prev_row = Some(y);
        prev_start = row_start;
        row_start = row_end;
    }
    let mut k = keep.iter();
    pixels.retain(|_| k.next().copied().unwrap_or(false));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bright_stripe_is_found_at_its_centre_and_a_step_edge_is_not() {
        let (w, h) = (80, 3);
        let mut img = Image::new(w, h).unwrap();
        for y in 0..h {
            for x in 0..w {
                // Stripe 5 px wide centred on x = 30; a step from 60 on.
                let v = if (28..=32).contains(&x) || x >= 60 {
                    200
                } else {
                    80
                };
                img.set(x, y, v);
            }
        }
        let mut out = Vec::new();
        find_ridges(&img, 0..h, 20, &mut Vec::new(), &mut out);
        assert_eq!(out.len(), h, "one pixel per row: {out:?}");
        assert!(
            out.iter().all(|p| p.x == 30 && p.contrast == 120),
            "{out:?}"
        );
        // Too faint.
        out.clear();
        find_ridges(&img, 0..h, 121, &mut Vec::new(), &mut out);
        assert!(out.is_empty());
    }

    #[test]
    fn isolated_ridges_go_and_runs_stay() {
        let px = |x, y| RidgePixel { x, y, contrast: 50 };
        // A run down rows 0-3 drifting one column a row; a lone pixel on row 1; a pair of rows
        // too far apart in x.
        let mut pixels = vec![
            px(10, 0),
            px(40, 0),
            px(11, 1),
            px(70, 1),
            px(12, 2),
            px(13, 3),
            px(30, 3),
            px(36, 4),
        ];
        keep_continuous(&mut pixels, 2);
        let xs: Vec<u16> = pixels.iter().map(|p| p.x).collect();
        assert_eq!(xs, vec![10, 11, 12, 13]);
    }
}
