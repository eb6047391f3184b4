//! The marking-intensity image at working resolution.
//!
//! Lane paint is white or yellow. White is bright in the luma Y; yellow on light concrete is
//! not, but it is where blue is low, so each pixel's marking intensity is
//!
//! ```text
//! m = max(Y, clamp(2 ((R + G) / 2 - B), 0, 255))
//! ```
//!
//! (grey road and white paint have R = G = B, so the second term is zero on them). Beside it,
//! in the same pass, each pixel's saturation
//!
//! ```text
//! sat = 255 (max(R, G, B) - min(R, G, B)) / max(max(R, G, B), 40)
//! ```
//!
//! (the floor keeps dark noise from looking colourful), which tells grey road from foliage,
//! sky and car paint (see [`super::road_colour`]). Both images are then box-averaged over
//! s x s blocks, with s the smallest integer that brings the width to at most
//! [`MAX_WORK_WIDTH`]: the calibrator needs line directions, not fine detail, and this keeps
//! the later steps' cost independent of the video's resolution. This pass reads every pixel
//! (four at a time, [`super::marking_pixels`]) and is the largest part of the calibrator's
//! time, so the rows above the road (the sky, once the calibrator knows the horizon) are
//! skipped.

use super::marking_pixels::marking_pixels;
use crate::error::Result;
use crate::image::{check_rgba, Image};

/// Widest working image, pixels.
pub const MAX_WORK_WIDTH: usize = 480;

/// The block size s for a frame `width` pixels wide.
pub fn working_scale(width: usize) -> usize {
    width.div_ceil(MAX_WORK_WIDTH).max(1)
}

/// Scratch of [`marking_intensity`], kept by its caller so that frames allocate nothing: the
/// block sums of one working row and one source row's per-pixel values.
#[derive(Debug, Clone, Default)]
pub struct MarkingScratch {
    sums: Vec<[u32; 2]>,
    intensity: Vec<u8>,
    saturation: Vec<u8>,
}

/// Writes the s x s block means of the marking intensity of `rgba` into `out` and those of its
/// saturation into `sat`, both resized to (width / s) x (height / s) (the last partial block of
/// a row or column is dropped), for the working rows from `first_row` down; the rows above it
/// (the sky, when the caller knows where the road ends) are zero in both.
///
/// # Errors
/// As [`check_rgba`]; [`crate::Error::Dimensions`] when the frame is smaller than one block.
#[allow(clippy::too_many_arguments)]
pub fn marking_intensity(
    rgba: &[u8],
    width: usize,
    height: usize,
    s: usize,
    first_row: usize,
    scratch: &mut MarkingScratch,
    out: &mut Image<u8>,
    sat: &mut Image<u8>,
) -> Result<()> {
    check_rgba(rgba, width, height)?;
    let (w, h) = (width / s, height / s);
    for image in [&mut *out, &mut *sat] {
        if image.width() != w || image.height() != h {
            image.resize(w, h)?;
        }
    }
    let first_row = first_row.min(h);
    for image in [&mut *out, &mut *sat] {
        for y in 0..first_row {
            image.row_mut(y).fill(0);
        }
    }
    let MarkingScratch {
        sums,
        intensity,
        saturation,
    } = scratch;
    sums.clear();
    sums.resize(w, [0, 0]);
    intensity.resize(w * s, 0);
    saturation.resize(w * s, 0);
    let area = (s * s) as u32;
    for y in first_row..h {
        sums.iter_mut().for_each(|v| *v = [0, 0]);
        for row in 0..s {
            let start = ((y * s + row) * width) * 4;
            marking_pixels(&rgba[start..start + w * s * 4], intensity, saturation);
            for ((sum, block_m), block_s) in sums
                .iter_mut()
                .zip(intensity.chunks_exact(s))
                .zip(saturation.chunks_exact(s))
            {
                sum[0] += block_m.iter().map(|&v| u32::from(v)).sum::<u32>();
                sum[1] += block_s.iter().map(|&v| u32::from(v)).sum::<u32>();
            }
        }
        for (k, image) in [&mut *out, &mut *sat].into_iter().enumerate() {
            for (o, v) in image.row_mut(y).iter_mut().zip(sums.iter()) {
                *o = ((v[k] + area / 2) / area) as u8;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yellow_is_bright_on_concrete_and_blocks_are_averaged() {
        assert_eq!(working_scale(640), 2);
        assert_eq!(working_scale(480), 1);
        assert_eq!(working_scale(1280), 3);
        assert_eq!(working_scale(1), 1);
        // 4x2 frame, s = 2: left block light grey concrete, right block yellow paint.
        let concrete = [170u8, 170, 170, 255];
        let yellow = [220u8, 200, 50, 255];
        let mut rgba = Vec::new();
        for _ in 0..2 {
            rgba.extend_from_slice(&concrete);
            rgba.extend_from_slice(&concrete);
            rgba.extend_from_slice(&yellow);
            rgba.extend_from_slice(&yellow);
        }
        let (mut out, mut sat) = (Image::new(1, 1).unwrap(), Image::new(1, 1).unwrap());
        marking_intensity(
            &rgba,
            4,
            2,
            2,
            0,
            &mut MarkingScratch::default(),
            &mut out,
            &mut sat,
        )
        .unwrap();
        assert_eq!((out.width(), out.height()), (2, 1));
        assert_eq!((sat.width(), sat.height()), (2, 1));
        assert_eq!(out.get(0, 0), 170);
        assert_eq!(out.get(1, 0), 255, "yellow stands out on concrete");
        assert_eq!(sat.get(0, 0), 0, "concrete is grey");
        // 255 (220 - 50) / 220 = 197.
        assert_eq!(sat.get(1, 0), 197);
        assert!(marking_intensity(
            &rgba,
            4,
            3,
            2,
            0,
            &mut MarkingScratch::default(),
            &mut out,
            &mut sat
        )
        .is_err());
    }
}
