//! The errors the binding throws: a JavaScript `Error` with a readable message and its kind in
//! `error.name` (`LanepfConfigError`, `LanepfInputError`, `LanepfStateError`), so callers can
//! branch on the kind instead of on the message text.

use wasm_bindgen::JsValue;

/// What a thrown error is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A constructor's argument or option object: a tracker id, a scenario name, a camera, a
    /// tracker config, scene, test-road or calibrator options (unknown keys, wrong types,
    /// values out of range, an unknown id).
    Config,
    /// A call's data: a frame (type, length, size), a frame index, a pixel or road point, the
    /// ego motion, a count.
    Input,
    /// A call the object cannot take now or at all: `advance()` with no frame in progress, a
    /// stereo tracker's step without its right frame, a right frame for a one-camera tracker.
    State,
}

impl Kind {
    /// The JavaScript `error.name` of this kind.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Config => "LanepfConfigError",
            Kind::Input => "LanepfInputError",
            Kind::State => "LanepfStateError",
        }
    }
}

/// An error on its way to JavaScript, where it becomes a thrown `Error` with
/// `name = kind.name()`.
#[derive(Debug, Clone, PartialEq)]
pub struct Thrown {
    kind: Kind,
    message: String,
}

impl Thrown {
    /// An error of `kind` with `message`.
    pub fn new(kind: Kind, message: impl Into<String>) -> Self {
        Thrown {
            kind,
            message: message.into(),
        }
    }

    /// A [`Kind::Config`] error.
    pub fn config(message: impl Into<String>) -> Self {
        Thrown::new(Kind::Config, message)
    }

    /// A [`Kind::Input`] error.
    pub fn input(message: impl Into<String>) -> Self {
        Thrown::new(Kind::Input, message)
    }

    /// The kind.
    pub fn kind(&self) -> Kind {
        self.kind
    }

    /// The message.
    pub fn message(&self) -> &str {
        &self.message
    }
}

/// A core error keeps its message; its kind follows the variant: a bad configuration, parameter
/// or id is [`Kind::Config`], a wrong state [`Kind::State`], anything about data
/// [`Kind::Input`]. Call sites that know better (a parameter of a call, not of a constructor)
/// use `input`.
impl From<crate::Error> for Thrown {
    fn from(e: crate::Error) -> Self {
        use crate::Error as E;
        let kind = match e {
            E::Config(_) | E::Parameter { .. } | E::UnknownTracker { .. } => Kind::Config,
            E::State(_) => Kind::State,
            E::Dimensions(_)
            | E::BufferSize { .. }
            | E::Geometry(_)
            | E::Io { .. }
            | E::Decode { .. } => Kind::Input,
        };
        Thrown::new(kind, e.to_string())
    }
}

impl From<Thrown> for JsValue {
    fn from(t: Thrown) -> JsValue {
        let error = js_sys::Error::new(&t.message);
        error.set_name(t.kind.name());
        error.into()
    }
}

/// A core error in a constructor: [`Kind::Config`] whatever its variant (a camera of 0x480
/// pixels is a bad option, not bad data).
pub fn config(e: crate::Error) -> Thrown {
    Thrown::new(Kind::Config, e.to_string())
}

/// A core error about a call's data ([`Kind::Input`] whatever its variant), except a wrong
/// state, which stays [`Kind::State`].
pub fn input(e: crate::Error) -> Thrown {
    let t = Thrown::from(e);
    match t.kind {
        Kind::State => t,
        _ => Thrown::new(Kind::Input, t.message),
    }
}
