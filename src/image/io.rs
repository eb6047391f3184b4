//! Reading image files (PNG, JPEG) into grey or RGBA buffers, and writing PNGs.

use super::buffer::{check_dimensions, Image};
use crate::error::{Error, Result};
use std::path::Path;

/// An RGBA frame decoded from a file or memory.
#[derive(Debug, Clone)]
pub struct RgbaFrame {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// width * height * 4 bytes.
    pub data: Vec<u8>,
}

/// Decodes PNG or JPEG bytes. `name` is only used in error messages. The size in the file's
/// header is checked before anything is decoded, so a small file that claims a huge image is
/// refused at once instead of after allocating it. A truncated JPEG is an error: the JPEG
/// decoder fills the missing part with grey and would otherwise give a frame silently.
///
/// # Errors
/// [`Error::Decode`] for a corrupt, truncated or unsupported file; [`Error::Dimensions`] for
/// an unusable size.
pub fn decode_rgba(bytes: &[u8], name: &str) -> Result<RgbaFrame> {
    let decode_error = |e: image::ImageError| Error::Decode {
        path: name.to_string(),
        reason: e.to_string(),
    };
    let reader = || {
        image::ImageReader::new(std::io::Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| Error::Decode {
                path: name.to_string(),
                reason: e.to_string(),
            })
    };
    let (hw, hh) = reader()?.into_dimensions().map_err(decode_error)?;
    check_dimensions(hw as usize, hh as usize)
        .map_err(|e| Error::Dimensions(format!("{name}: {e}")))?;
    if bytes.starts_with(&[0xff, 0xd8]) && !jpeg_is_complete(bytes) {
        return Err(Error::Decode {
            path: name.to_string(),
            reason: "the JPEG data ends before its end-of-image marker (the file is truncated)"
                .into(),
        });
    }
    let img = reader()?.decode().map_err(decode_error)?;
    let rgba = img.to_rgba8();
    let (w, h) = (rgba.width() as usize, rgba.height() as usize);
    check_dimensions(w, h)?;
    Ok(RgbaFrame {
        width: w,
        height: h,
        data: rgba.into_raw(),
    })
}

/// Whether a JPEG's last scan is followed by its end-of-image marker (FF D9). Inside
/// entropy-coded data a 0xFF byte is only ever followed by 0x00 or a restart marker, so FF DA
/// (start of scan) and FF D9 are markers wherever they appear; an embedded thumbnail's markers
/// come before the main image's last scan.
fn jpeg_is_complete(bytes: &[u8]) -> bool {
    let last_scan = bytes.windows(2).rposition(|w| w == [0xff, 0xda]);
    last_scan.is_some_and(|at| bytes[at..].windows(2).any(|w| w == [0xff, 0xd9]))
}

/// Reads and decodes an image file.
///
/// # Errors
/// [`Error::Io`] when the file cannot be read, otherwise as [`decode_rgba`].
pub fn read_rgba(path: &Path) -> Result<RgbaFrame> {
    let bytes = std::fs::read(path).map_err(|e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })?;
    decode_rgba(&bytes, &path.display().to_string())
}

/// Writes a grey image as PNG.
///
/// # Errors
/// [`Error::Io`] when the file cannot be written.
pub fn write_gray_png(path: &Path, img: &Image<u8>) -> Result<()> {
    image::save_buffer(
        path,
        img.data(),
        img.width() as u32,
        img.height() as u32,
        image::ExtendedColorType::L8,
    )
    .map_err(|e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })
}

/// Writes an RGBA buffer as PNG.
///
/// # Errors
/// [`Error::BufferSize`] for a wrong length, [`Error::Io`] when the file cannot be written.
pub fn write_rgba_png(path: &Path, rgba: &[u8], width: usize, height: usize) -> Result<()> {
    super::rgba::check_rgba(rgba, width, height)?;
    image::save_buffer(
        path,
        rgba,
        width as u32,
        height as u32,
        image::ExtendedColorType::Rgba8,
    )
    .map_err(|e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })
}

/// Writes a disparity map as a 16-bit grey PNG in the KITTI convention: value = round(256 d),
/// 0 where the disparity is unknown (d <= 0 or not finite); disparities above 255.99 saturate.
///
/// # Errors
/// [`Error::BufferSize`] for a wrong length, [`Error::Io`] when the file cannot be written.
pub fn write_disparity_png(
    path: &Path,
    disparity: &[f32],
    width: usize,
    height: usize,
) -> Result<()> {
    check_dimensions(width, height)?;
    if disparity.len() != width * height {
        return Err(Error::BufferSize {
            what: format!("a {width}x{height} disparity map"),
            expected: width * height,
            actual: disparity.len(),
        });
    }
    let data: Vec<u16> = disparity
        .iter()
        .map(|&d| {
            if d.is_finite() && d > 0.0 {
                (d * 256.0).round().clamp(1.0, 65535.0) as u16
            } else {
                0
            }
        })
        .collect();
    let img = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(
        width as u32,
        height as u32,
        data,
    )
    .ok_or_else(|| Error::Dimensions(format!("{width}x{height}")))?;
    img.save(path).map_err(|e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })
}

/// Reads a KITTI-convention 16-bit disparity PNG (0 becomes 0.0: unknown).
///
/// # Errors
/// [`Error::Io`] / [`Error::Decode`] when the file cannot be read or is not a grey image.
pub fn read_disparity_png(path: &Path) -> Result<(Vec<f32>, usize, usize)> {
    let img = image::open(path).map_err(|e| Error::Decode {
        path: path.display().to_string(),
        reason: e.to_string(),
    })?;
    let g = img.to_luma16();
    let (w, h) = (g.width() as usize, g.height() as usize);
    Ok((
        g.into_raw().into_iter().map(|v| v as f32 / 256.0).collect(),
        w,
        h,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CRC-32 (IEEE) of `bytes`, for hand-made PNG chunks.
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = 0xffff_ffffu32;
        for &b in bytes {
            c ^= b as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xedb8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }

    /// A PNG whose header claims `w` x `h` RGBA pixels, with an empty IDAT: no image data.
    fn png_header(w: u32, h: u32) -> Vec<u8> {
        let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
        let mut ihdr = b"IHDR".to_vec();
        ihdr.extend_from_slice(&w.to_be_bytes());
        ihdr.extend_from_slice(&h.to_be_bytes());
        ihdr.extend_from_slice(&[8, 6, 0, 0, 0]);
        out.extend_from_slice(&13u32.to_be_bytes());
        out.extend_from_slice(&ihdr);
        out.extend_from_slice(&crc32(&ihdr).to_be_bytes());
        for chunk in [&b"IDAT"[..], &b"IEND"[..]] {
            out.extend_from_slice(&0u32.to_be_bytes());
            out.extend_from_slice(chunk);
            out.extend_from_slice(&crc32(chunk).to_be_bytes());
        }
        out
    }

    #[test]
    fn a_huge_size_in_the_header_is_refused_before_decoding() {
        assert_eq!(
            crc32(b"IEND"),
            0xae42_6082,
            "the CRC of IEND, as every PNG ends"
        );
        let start = std::time::Instant::now();
        let e = decode_rgba(&png_header(22_000, 22_000), "big.png").unwrap_err();
        assert!(matches!(e, Error::Dimensions(_)), "{e}");
        assert!(
            e.to_string().contains("big.png") && e.to_string().contains("22000x22000"),
            "{e}"
        );
        // Within the limits, the same header gets as far as the (missing) data.
        let e = decode_rgba(&png_header(64, 48), "small.png").unwrap_err();
        assert!(matches!(e, Error::Decode { .. }), "{e}");
        assert!(start.elapsed().as_secs_f64() < 1.0);
    }

    #[test]
    fn a_truncated_jpeg_is_an_error_naming_the_file() {
        let rgb: Vec<u8> = (0..64 * 48 * 3).map(|k| (k * 7 % 251) as u8).collect();
        let mut jpeg = Vec::new();
        image::codecs::jpeg::JpegEncoder::new_with_quality(&mut jpeg, 90)
            .encode(&rgb, 64, 48, image::ExtendedColorType::Rgb8)
            .unwrap();
        assert_eq!(decode_rgba(&jpeg, "whole.jpg").unwrap().width, 64);
        for cut in [jpeg.len() - 2, jpeg.len() * 2 / 3, 700] {
            let e = decode_rgba(&jpeg[..cut], "cut.jpg")
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("cut.jpg") && e.contains("truncated"),
                "{cut}: {e}"
            );
        }
    }

    #[test]
    fn corrupt_bytes_give_a_decode_error() {
        let e = decode_rgba(b"\x89PNG\r\n\x1a\nnot really", "x.png").unwrap_err();
        assert!(matches!(e, Error::Decode { .. }), "{e}");
        let e = read_rgba(Path::new("/nonexistent/x.png")).unwrap_err();
        assert!(matches!(e, Error::Io { .. }));
    }

    #[test]
    fn disparity_png_round_trip_keeps_a_256th_of_a_pixel() {
        let dir = std::env::temp_dir().join(format!("lanepf-disp-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("d.png");
        let d = [0.0, 1.5, 37.123, f32::NAN, -2.0, 300.0];
        write_disparity_png(&path, &d, 3, 2).unwrap();
        let (back, w, h) = read_disparity_png(&path).unwrap();
        assert_eq!((w, h), (3, 2));
        assert_eq!(&back[..2], &[0.0, 1.5]);
        assert!((back[2] - 37.123).abs() <= 0.5 / 256.0);
        assert_eq!(&back[3..5], &[0.0, 0.0]);
        assert!((back[5] - 65535.0 / 256.0).abs() < 1e-3, "saturates");
        assert!(write_disparity_png(&path, &d, 2, 2).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn png_round_trip() {
        let dir = std::env::temp_dir().join(format!("lanepf-io-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("t.png");
        let rgba: Vec<u8> = (0..2 * 3 * 4).map(|i| (i * 10) as u8).collect();
        write_rgba_png(&p, &rgba, 2, 3).unwrap();
        let back = read_rgba(&p).unwrap();
        assert_eq!((back.width, back.height), (2, 3));
        assert_eq!(back.data, rgba);
        std::fs::remove_dir_all(&dir).ok();
    }
}
