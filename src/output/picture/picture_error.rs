//! Why a picture could not be drawn.

/// Why a picture could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PictureError {
    /// The results handed over do not belong to the model (a caller's bug).
    #[error("the run's {what} do not match its model")]
    Mismatch { what: &'static str },
    /// Nothing to draw.
    #[error("{0}")]
    Empty(String),
    #[error("the embedded font has no readable metrics")]
    Font,
    #[error("writing \"{text}\" on the picture: {reason}")]
    Text { text: String, reason: String },
    #[error("encoding the PNG: {0}")]
    Png(#[from] png::EncodingError),
    #[error("drawing the interface plot: {0}")]
    Plot(#[from] crate::output::plot::PlotError),
}
