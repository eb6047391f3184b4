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

/// Decodes PNG or JPEG bytes. `name` is only used in error messages.
///
/// # Errors
/// [`Error::Decode`] for a corrupt or unsupported file; [`Error::Dimensions`] for an unusable size.
pub fn decode_rgba(bytes: &[u8], name: &str) -> Result<RgbaFrame> {
    let img = image::load_from_memory(bytes).map_err(|e| Error::Decode {
        path: name.to_string(),
        reason: e.to_string(),
    })?;
    let rgba = img.to_rgba8();
    let (w, h) = (rgba.width() as usize, rgba.height() as usize);
    check_dimensions(w, h)?;
    Ok(RgbaFrame {
        width: w,
        height: h,
        data: rgba.into_raw(),
    })
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corrupt_bytes_give_a_decode_error() {
        let e = decode_rgba(b"\x89PNG\r\n\x1a\nnot really", "x.png").unwrap_err();
        assert!(matches!(e, Error::Decode { .. }), "{e}");
        let e = read_rgba(Path::new("/nonexistent/x.png")).unwrap_err();
        assert!(matches!(e, Error::Io { .. }));
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
