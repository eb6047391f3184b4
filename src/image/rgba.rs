//! RGBA input frames and their conversion to grey.
//!
//! Browsers hand frames over as `ImageData.data`: 4 bytes per pixel (R, G, B, A), row-major.
//! Grey is the Rec. 601 luma Y = 0.299 R + 0.587 G + 0.114 B, computed in fixed point as
//! (77 R + 150 G + 29 B + 128) >> 8 (weights sum to 256), alpha ignored.

use super::buffer::{check_dimensions, Image};
use crate::error::{Error, Result};

/// Checks that `rgba` holds exactly `width * height * 4` bytes.
///
/// # Errors
/// [`Error::Dimensions`] or [`Error::BufferSize`], with the expected length in the message.
pub fn check_rgba(rgba: &[u8], width: usize, height: usize) -> Result<()> {
    check_dimensions(width, height)?;
    let expected = width * height * 4;
    if rgba.len() != expected {
        return Err(Error::BufferSize {
            what: format!("a {width}x{height} RGBA frame (width*height*4 bytes)"),
            expected,
            actual: rgba.len(),
        });
    }
    Ok(())
}

/// Rec. 601 luma of one pixel in fixed point.
#[inline]
pub fn luma(r: u8, g: u8, b: u8) -> u8 {
    ((77 * r as u32 + 150 * g as u32 + 29 * b as u32 + 128) >> 8) as u8
}

/// Converts an RGBA frame into `out`, resizing `out` (without reallocating when it is already
/// large enough).
///
/// # Errors
/// See [`check_rgba`].
pub fn rgba_to_gray(rgba: &[u8], width: usize, height: usize, out: &mut Image<u8>) -> Result<()> {
    check_rgba(rgba, width, height)?;
    if out.width() != width || out.height() != height {
        out.resize(width, height)?;
    }
    for (px, g) in rgba.chunks_exact(4).zip(out.data_mut().iter_mut()) {
        *g = luma(px[0], px[1], px[2]);
    }
    Ok(())
}

/// [`rgba_to_gray`] of the rows `rows` alone (clipped to the frame): the other rows of `out`
/// keep what they held (zeros in a new image). For a reader of only those rows, such as an
/// IPM ([`crate::vision::Ipm::source_rows`]).
///
/// # Errors
/// See [`check_rgba`].
pub fn rgba_to_gray_rows(
    rgba: &[u8],
    width: usize,
    height: usize,
    rows: std::ops::Range<usize>,
    out: &mut Image<u8>,
) -> Result<()> {
    check_rgba(rgba, width, height)?;
    if out.width() != width || out.height() != height {
        out.resize(width, height)?;
    }
    let (first, end) = (rows.start.min(height), rows.end.min(height));
    if first >= end {
        return Ok(());
    }
    let grey = &mut out.data_mut()[first * width..end * width];
    for (px, g) in rgba[first * width * 4..end * width * 4]
        .chunks_exact(4)
        .zip(grey.iter_mut())
    {
        *g = luma(px[0], px[1], px[2]);
    }
    Ok(())
}

/// Expands a grey image to opaque RGBA (for drawing intermediate images on a canvas).
pub fn gray_to_rgba(gray: &Image<u8>, out: &mut Vec<u8>) {
    out.clear();
    out.reserve(gray.data().len() * 4);
    for &g in gray.data() {
        out.extend_from_slice(&[g, g, g, 255]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luma_weights_sum_to_one() {
        assert_eq!(luma(255, 255, 255), 255);
        assert_eq!(luma(0, 0, 0), 0);
        assert_eq!(luma(255, 0, 0), 77);
        assert_eq!(luma(0, 255, 0), 149);
        assert_eq!(luma(0, 0, 255), 29);
    }

    #[test]
    fn converts_and_checks_length() {
        let rgba = [255, 255, 255, 0, 0, 0, 0, 255, 10, 20, 30, 255];
        let mut g = Image::new(1, 1).unwrap();
        rgba_to_gray(&rgba, 3, 1, &mut g).unwrap();
        assert_eq!(g.data(), &[255, 0, luma(10, 20, 30)]);
        let e = rgba_to_gray(&rgba[..11], 3, 1, &mut g).unwrap_err();
        assert!(e.to_string().contains("needs 12"), "{e}");
        assert!(rgba_to_gray(&[], 0, 0, &mut g).is_err());
    }

    #[test]
    fn converts_only_the_rows_asked_for() {
        let rgba: Vec<u8> = (0..3 * 4 * 4).map(|i| (i * 7 % 256) as u8).collect();
        let mut all = Image::new(1, 1).unwrap();
        rgba_to_gray(&rgba, 3, 4, &mut all).unwrap();
        let mut some = Image::new(3, 4).unwrap();
        rgba_to_gray_rows(&rgba, 3, 4, 1..3, &mut some).unwrap();
        assert_eq!(&some.data()[3..9], &all.data()[3..9]);
        assert_eq!(&some.data()[..3], &[0; 3]);
        assert_eq!(&some.data()[9..], &[0; 3]);
        rgba_to_gray_rows(&rgba, 3, 4, 2..9, &mut some).unwrap();
        assert_eq!(&some.data()[6..], &all.data()[6..]);
        assert!(rgba_to_gray_rows(&rgba[..5], 3, 4, 0..1, &mut some).is_err());
    }
}
