//! Owned images and borrowed views with validated dimensions and stride.
//!
//! A pixel (x, y) of an image with stride s lives at `data[y * s + x]`; x runs right, y down,
//! origin top-left, pixel centres at integer coordinates. Owned images are allocated once and
//! reused (`resize` only reallocates when the size grows), so per-frame code writes into them.

use crate::error::{Error, Result};

/// Largest accepted width or height, in pixels.
pub const MAX_SIDE: usize = 16_384;
/// Largest accepted pixel count (width * height): 64 megapixels.
pub const MAX_PIXELS: usize = 1 << 26;

/// Checks that `width` x `height` is a usable image size.
///
/// # Errors
/// [`Error::Dimensions`] when a side is zero, larger than [`MAX_SIDE`], or the area exceeds
/// [`MAX_PIXELS`].
pub fn check_dimensions(width: usize, height: usize) -> Result<()> {
    if width == 0 || height == 0 {
        return Err(Error::Dimensions(format!(
            "{width}x{height}: width and height must both be at least 1"
        )));
    }
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(Error::Dimensions(format!(
            "{width}x{height}: each side must be at most {MAX_SIDE} pixels"
        )));
    }
    if width * height > MAX_PIXELS {
        return Err(Error::Dimensions(format!(
            "{width}x{height}: at most {MAX_PIXELS} pixels are accepted"
        )));
    }
    Ok(())
}

/// An owned single-channel image.
#[derive(Debug, Clone, PartialEq)]
pub struct Image<T> {
    width: usize,
    height: usize,
    data: Vec<T>,
}

impl<T: Copy + Default> Image<T> {
    /// A `width` x `height` image filled with `T::default()`.
    ///
    /// # Errors
    /// [`Error::Dimensions`] for an unusable size (see [`check_dimensions`]).
    pub fn new(width: usize, height: usize) -> Result<Self> {
        check_dimensions(width, height)?;
        Ok(Self {
            width,
            height,
            data: vec![T::default(); width * height],
        })
    }

    /// Wraps `data` (row-major, stride = width).
    ///
    /// # Errors
    /// [`Error::Dimensions`] or [`Error::BufferSize`] when `data` does not hold width*height values.
    pub fn from_vec(width: usize, height: usize, data: Vec<T>) -> Result<Self> {
        check_dimensions(width, height)?;
        if data.len() != width * height {
            return Err(Error::BufferSize {
                what: format!("a {width}x{height} image"),
                expected: width * height,
                actual: data.len(),
            });
        }
        Ok(Self {
            width,
            height,
            data,
        })
    }

    /// Changes the size, keeping the allocation when it is large enough. Contents are reset to
    /// `T::default()`.
    ///
    /// # Errors
    /// [`Error::Dimensions`] for an unusable size.
    pub fn resize(&mut self, width: usize, height: usize) -> Result<()> {
        check_dimensions(width, height)?;
        self.width = width;
        self.height = height;
        self.data.clear();
        self.data.resize(width * height, T::default());
        Ok(())
    }

    /// Sets every pixel to `value`.
    pub fn fill(&mut self, value: T) {
        self.data.fill(value);
    }
}

impl<T: Copy> Image<T> {
    /// Width in pixels.
    #[inline]
    pub fn width(&self) -> usize {
        self.width
    }
    /// Height in pixels.
    #[inline]
    pub fn height(&self) -> usize {
        self.height
    }
    /// Row-major pixels (stride = width).
    #[inline]
    pub fn data(&self) -> &[T] {
        &self.data
    }
    /// Mutable row-major pixels.
    #[inline]
    pub fn data_mut(&mut self) -> &mut [T] {
        &mut self.data
    }
    /// Pixel (x, y). Panics when out of range (callers iterate inside the image).
    #[inline]
    pub fn get(&self, x: usize, y: usize) -> T {
        self.data[y * self.width + x]
    }
    /// Sets pixel (x, y). Panics when out of range.
    #[inline]
    pub fn set(&mut self, x: usize, y: usize, v: T) {
        self.data[y * self.width + x] = v;
    }
    /// Row y as a slice.
    #[inline]
    pub fn row(&self, y: usize) -> &[T] {
        &self.data[y * self.width..(y + 1) * self.width]
    }
    /// Row y as a mutable slice.
    #[inline]
    pub fn row_mut(&mut self, y: usize) -> &mut [T] {
        let w = self.width;
        &mut self.data[y * w..(y + 1) * w]
    }
    /// A borrowed view of the whole image.
    pub fn view(&self) -> ImageView<'_, T> {
        ImageView {
            width: self.width,
            height: self.height,
            stride: self.width,
            data: &self.data,
        }
    }
    /// The same size as `other`?
    pub fn same_size<U: Copy>(&self, other: &Image<U>) -> bool {
        self.width == other.width && self.height == other.height
    }
}

/// A borrowed single-channel image with an explicit row stride (in elements).
#[derive(Debug, Clone, Copy)]
pub struct ImageView<'a, T> {
    width: usize,
    height: usize,
    stride: usize,
    data: &'a [T],
}

impl<'a, T: Copy> ImageView<'a, T> {
    /// A view of `data` as `width` x `height` pixels with rows `stride` elements apart.
    ///
    /// # Errors
    /// [`Error::Dimensions`] when the size is unusable or `stride < width`;
    /// [`Error::BufferSize`] when `data` is too short for the last row.
    pub fn new(data: &'a [T], width: usize, height: usize, stride: usize) -> Result<Self> {
        check_dimensions(width, height)?;
        if stride < width {
            return Err(Error::Dimensions(format!(
                "stride {stride} is smaller than the width {width}"
            )));
        }
        let needed = (height - 1) * stride + width;
        if data.len() < needed {
            return Err(Error::BufferSize {
                what: format!("a {width}x{height} view with stride {stride}"),
                expected: needed,
                actual: data.len(),
            });
        }
        Ok(Self {
            width,
            height,
            stride,
            data,
        })
    }
    /// Width in pixels.
    #[inline]
    pub fn width(&self) -> usize {
        self.width
    }
    /// Height in pixels.
    #[inline]
    pub fn height(&self) -> usize {
        self.height
    }
    /// Row stride in elements.
    #[inline]
    pub fn stride(&self) -> usize {
        self.stride
    }
    /// Pixel (x, y). Panics when out of range.
    #[inline]
    pub fn get(&self, x: usize, y: usize) -> T {
        self.data[y * self.stride + x]
    }
    /// The underlying elements from pixel (0, 0) on; pixel (x, y) is at `y * stride + x`.
    #[inline]
    pub fn as_slice(&self) -> &'a [T] {
        self.data
    }
    /// Row y (exactly `width` elements).
    #[inline]
    pub fn row(&self, y: usize) -> &'a [T] {
        &self.data[y * self.stride..y * self.stride + self.width]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_zero_huge_and_mismatched_sizes() {
        assert!(matches!(Image::<u8>::new(0, 10), Err(Error::Dimensions(_))));
        assert!(matches!(
            Image::<u8>::new(MAX_SIDE + 1, 1),
            Err(Error::Dimensions(_))
        ));
        assert!(matches!(
            Image::<u8>::new(MAX_SIDE, MAX_SIDE),
            Err(Error::Dimensions(_))
        ));
        let e = Image::from_vec(4, 3, vec![0u8; 11]).unwrap_err();
        assert_eq!(
            e,
            Error::BufferSize {
                what: "a 4x3 image".into(),
                expected: 12,
                actual: 11
            }
        );
    }

    #[test]
    fn views_honour_stride() {
        let data: Vec<u8> = (0..20).collect();
        let v = ImageView::new(&data, 3, 4, 5).unwrap();
        assert_eq!(v.get(2, 3), 17);
        assert_eq!(v.row(1), &[5, 6, 7]);
        assert!(ImageView::new(&data, 6, 4, 5).is_err());
        assert!(ImageView::new(&data[..17], 3, 4, 5).is_err());
    }

    #[test]
    fn resize_keeps_the_allocation_when_shrinking() {
        let mut im = Image::<f32>::new(64, 64).unwrap();
        let cap = im.data.capacity();
        im.resize(32, 16).unwrap();
        assert_eq!((im.width(), im.height(), im.data().len()), (32, 16, 512));
        assert_eq!(im.data.capacity(), cap);
    }
}
