//! The raster the deformed picture and the plan views are drawn on: an RGB
//! buffer with filled triangles (linearly shaded, or painted from each
//! pixel's barycentric weights), anti-aliased lines and dots, text written by
//! plotters in the embedded DejaVu Sans (placed by the font's own metrics),
//! and its encoding as a PNG by the `png` crate.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::colours::INK;
use super::picture_error::PictureError;

/// Text to write once the raster is done.
pub(super) struct Label {
    pub(super) text: String,
    at: (f64, f64),
    size: f64,
    pos: (HPos, VPos),
}

pub(super) fn label(text: impl Into<String>, at: (f64, f64), size: f64, pos: (HPos, VPos)) -> Label {
    Label { text: capped(text.into()), at, size, pos }
}

/// Longest text drawn on a picture, in characters: a title a user made
/// huge (a 1 GB title was still being drawn after 12 minutes) is cut.
pub(super) const MAX_LABEL: usize = 160;

/// `text` cut to [`MAX_LABEL`] characters, with an ellipsis.
fn capped(mut text: String) -> String {
    if let Some((at, _)) = text.char_indices().nth(MAX_LABEL) {
        text.truncate(at);
        text.push('…');
    }
    text
}

pub(super) fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            include_bytes!("../../../assets/DejaVuSans.ttf"),
        );
    });
}

/// An RGB image, row by row from the top.
pub(super) struct Canvas {
    pub(super) w: usize,
    pub(super) h: usize,
    pub(super) rgb: Vec<u8>,
    /// The pixels drawing may touch: x0, y0, x1, y1 (x1, y1 excluded).
    clip: [usize; 4],
}

impl Canvas {
    pub(super) fn new(w: usize, h: usize) -> Canvas {
        Canvas { w, h, rgb: vec![255; w * h * 3], clip: [0, 0, w, h] }
    }

    /// Keeps drawing inside the box x0, y0, x1, y1 (pixels), or anywhere
    /// with None (an unrolled surface's facets repeated across its seam
    /// stop at the panel's edge).
    pub(super) fn clip(&mut self, b: Option<[f64; 4]>) {
        self.clip = match b {
            Some(b) => [
                b[0].max(0.0) as usize,
                b[1].max(0.0) as usize,
                (b[2].max(0.0) as usize).min(self.w),
                (b[3].max(0.0) as usize).min(self.h),
            ],
            None => [0, 0, self.w, self.h],
        };
    }

    #[inline]
    fn inside(&self, x: usize, y: usize) -> bool {
        x >= self.clip[0] && x < self.clip[2] && y >= self.clip[1] && y < self.clip[3]
    }

    #[inline]
    fn blend(&mut self, x: usize, y: usize, c: [u8; 3], a: f32) {
        if !self.inside(x, y) {
            return;
        }
        let i = (y * self.w + x) * 3;
        for (k, &ck) in c.iter().enumerate() {
            let o = self.rgb[i + k] as f32;
            self.rgb[i + k] = (o + (ck as f32 - o) * a + 0.5) as u8;
        }
    }

    pub(super) fn rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64, c: [u8; 3]) {
        for y in (y0.max(self.clip[1] as f64) as usize)..(y1.min(self.clip[3] as f64) as usize) {
            for x in (x0.max(self.clip[0] as f64) as usize)..(x1.min(self.clip[2] as f64) as usize) {
                self.blend(x, y, c, 1.0);
            }
        }
    }

    /// Fills a triangle, each pixel painted by the linearly interpolated
    /// value.
    pub(super) fn triangle(&mut self, p: [[f32; 2]; 3], t: [f32; 3], paint: &dyn Fn(f32) -> [u8; 3]) {
        if t[0] == t[1] && t[1] == t[2] {
            let flat = paint(t[0]);
            self.scan(p, |_| flat);
        } else {
            self.scan(p, |w| paint((w[0] * t[0] as f64 + w[1] * t[1] as f64 + w[2] * t[2] as f64) as f32));
        }
    }

    /// Fills a triangle, each pixel painted from its barycentric weights on
    /// the three vertices.
    pub(super) fn triangle_weighted(&mut self, p: [[f32; 2]; 3], paint: &dyn Fn([f64; 3]) -> [u8; 3]) {
        self.scan(p, paint);
    }

    /// Paints the pixels whose centres lie in a triangle. Barycentric
    /// weights in f64 about the first vertex, with a small tolerance, leave
    /// no pixel out between triangles sharing an edge.
    fn scan(&mut self, p: [[f32; 2]; 3], paint: impl Fn([f64; 3]) -> [u8; 3]) {
        let o = [p[0][0] as f64, p[0][1] as f64];
        let q = p.map(|v| [v[0] as f64 - o[0], v[1] as f64 - o[1]]);
        let area = q[1][0] * q[2][1] - q[1][1] * q[2][0];
        if area.is_nan() || area.abs() <= 1e-12 {
            return;
        }
        let xmin = p.iter().map(|v| v[0]).fold(f32::INFINITY, f32::min).floor().max(self.clip[0] as f32) as usize;
        let ymin = p.iter().map(|v| v[1]).fold(f32::INFINITY, f32::min).floor().max(self.clip[1] as f32) as usize;
        let xmax =
            (p.iter().map(|v| v[0]).fold(f32::NEG_INFINITY, f32::max).ceil() as isize).min(self.clip[2] as isize - 1);
        let ymax =
            (p.iter().map(|v| v[1]).fold(f32::NEG_INFINITY, f32::max).ceil() as isize).min(self.clip[3] as isize - 1);
        if xmax < xmin as isize || ymax < ymin as isize {
            return;
        }
        let inv = 1.0 / area;
        // weights of vertices 1 and 2 as affine functions of the pixel centre
        let (a1, b1) = (q[2][1] * inv, -q[2][0] * inv);
        let (a2, b2) = (-q[1][1] * inv, q[1][0] * inv);
        let eps = -1e-9;
        for y in ymin..=ymax as usize {
            let py = y as f64 + 0.5 - o[1];
            for x in xmin..=xmax as usize {
                let px = x as f64 + 0.5 - o[0];
                let w1 = a1 * px + b1 * py;
                let w2 = a2 * px + b2 * py;
                let w0 = 1.0 - w1 - w2;
                if w0 >= eps && w1 >= eps && w2 >= eps {
                    let i = (y * self.w + x) * 3;
                    self.rgb[i..i + 3].copy_from_slice(&paint([w0, w1, w2]));
                }
            }
        }
    }

    /// An anti-aliased line of the given width, round-capped or butt-ended.
    pub(super) fn segment(&mut self, a: [f32; 2], b: [f32; 2], width: f32, c: [u8; 3], alpha: f32, round: bool) {
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        if !len.is_finite() {
            return;
        }
        // long lines in short pieces keep the scanned boxes small
        let pieces = (len / 12.0).ceil().max(1.0) as usize;
        let r = 0.5 * width;
        for s in 0..pieces {
            let (f0, f1) = (s as f32 / pieces as f32, (s + 1) as f32 / pieces as f32);
            let p = [a[0] + (b[0] - a[0]) * f0, a[1] + (b[1] - a[1]) * f0];
            let q = [a[0] + (b[0] - a[0]) * f1, a[1] + (b[1] - a[1]) * f1];
            let caps = round && (s == 0 || s + 1 == pieces);
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            let l2 = dx * dx + dy * dy;
            let xmin = (p[0].min(q[0]) - r - 1.0).floor().max(0.0) as usize;
            let ymin = (p[1].min(q[1]) - r - 1.0).floor().max(0.0) as usize;
            let xmax = ((p[0].max(q[0]) + r + 1.0).ceil() as isize).min(self.w as isize - 1);
            let ymax = ((p[1].max(q[1]) + r + 1.0).ceil() as isize).min(self.h as isize - 1);
            for y in ymin as isize..=ymax {
                for x in xmin as isize..=xmax {
                    let (px, py) = (x as f32 + 0.5 - p[0], y as f32 + 0.5 - p[1]);
                    let t = if l2 > 0.0 { (px * dx + py * dy) / l2 } else { 0.0 };
                    // pieces own [f0, f1); the last also its end
                    if !caps && (!(0.0..=1.0).contains(&t) || (t == 1.0 && s + 1 != pieces)) {
                        continue;
                    }
                    if caps && ((s != 0 && t < 0.0) || (s + 1 != pieces && t >= 1.0)) {
                        continue;
                    }
                    let t = t.clamp(0.0, 1.0);
                    let d = (px - t * dx).hypot(py - t * dy);
                    let cover = (r + 0.5 - d).clamp(0.0, 1.0);
                    if cover > 0.0 {
                        self.blend(x as usize, y as usize, c, alpha * cover);
                    }
                }
            }
        }
    }

    pub(super) fn polyline(&mut self, pts: impl Iterator<Item = [f32; 2]>, width: f32, c: [u8; 3], alpha: f32) {
        let mut last: Option<[f32; 2]> = None;
        for p in pts {
            if let Some(q) = last {
                self.segment(q, p, width, c, alpha, false);
            }
            last = Some(p);
        }
    }

    /// A contact pair's mark: a dot in its state's colour, ringed in black.
    pub(super) fn state_dot(&mut self, at: [f32; 2], c: [u8; 3]) {
        self.dot(at, 4.6, [0, 0, 0]);
        self.dot(at, 3.4, c);
    }

    pub(super) fn dot(&mut self, p: [f32; 2], r: f32, c: [u8; 3]) {
        let (x0, x1) =
            ((p[0] - r - 1.0).floor().max(0.0) as isize, ((p[0] + r + 1.0).ceil() as isize).min(self.w as isize - 1));
        let (y0, y1) =
            ((p[1] - r - 1.0).floor().max(0.0) as isize, ((p[1] + r + 1.0).ceil() as isize).min(self.h as isize - 1));
        for y in y0..=y1 {
            for x in x0..=x1 {
                let d = (x as f32 + 0.5 - p[0]).hypot(y as f32 + 0.5 - p[1]);
                let cover = (r + 0.5 - d).clamp(0.0, 1.0);
                if cover > 0.0 {
                    self.blend(x as usize, y as usize, c, cover);
                }
            }
        }
    }

    /// Writes the labels with plotters (the embedded font), one glyph at a
    /// time: plotters 0.3.7 draws the glyphs of a string each shifted left
    /// by its whole-pixel left side bearing, which jumbles letter spacing
    /// ("op en") in bitmaps; placing them from the font's own metrics
    /// restores it.
    pub(super) fn text(&mut self, labels: &[Label]) -> Result<(), PictureError> {
        let (w, h) = (self.w as u32, self.h as u32);
        let metrics = FontMetrics::get().ok_or(PictureError::Font)?;
        let root = BitMapBackend::with_buffer(&mut self.rgb, (w, h)).into_drawing_area();
        for l in labels {
            let colour = rgb(INK);
            let style =
                TextStyle::from(("sans-serif", l.size).into_font()).color(&colour).pos(Pos::new(HPos::Left, l.pos.1));
            let k = l.size / metrics.height;
            let width: f64 = l.text.chars().map(|c| metrics.glyph(c).0 * k).sum();
            let mut pen = match l.pos.0 {
                HPos::Left => l.at.0,
                HPos::Center => l.at.0 - 0.5 * width,
                HPos::Right => l.at.0 - width,
            };
            let mut buf = [0u8; 4];
            for c in l.text.chars() {
                let (advance, lsb) = metrics.glyph(c);
                if !c.is_whitespace() {
                    let x = pen.round() as i32 + (lsb * k).floor() as i32;
                    root.draw_text(c.encode_utf8(&mut buf), &style, (x, l.at.1.round() as i32))
                        .map_err(|e| PictureError::Text { text: l.text.clone(), reason: format!("{e:?}") })?;
                }
                pen += advance * k;
            }
        }
        root.present().map_err(|e| PictureError::Text { text: String::new(), reason: format!("{e:?}") })?;
        Ok(())
    }
}

/// Horizontal metrics of the embedded font (TrueType `hhea`, `hmtx` and the
/// format-4 `cmap`), in font units.
pub(super) struct FontMetrics {
    /// Ascender minus descender: the unit ab_glyph scales a size by.
    pub(super) height: f64,
    /// Advance width and left side bearing of every glyph.
    hmtx: Vec<(f64, f64)>,
    /// cmap format 4 segments: (end, start, delta, range offset, its position).
    segments: Vec<(u16, u16, u16, u16, usize)>,
    cmap: &'static [u8],
}

impl FontMetrics {
    pub(super) fn get() -> Option<&'static FontMetrics> {
        static METRICS: std::sync::OnceLock<Option<FontMetrics>> = std::sync::OnceLock::new();
        METRICS.get_or_init(|| FontMetrics::parse(include_bytes!("../../../assets/DejaVuSans.ttf"))).as_ref()
    }

    fn parse(font: &'static [u8]) -> Option<FontMetrics> {
        let u16_at =
            |b: &[u8], at: usize| -> Option<u16> { Some(u16::from_be_bytes(b.get(at..at + 2)?.try_into().ok()?)) };
        let u32_at = |b: &[u8], at: usize| -> Option<usize> {
            Some(u32::from_be_bytes(b.get(at..at + 4)?.try_into().ok()?) as usize)
        };
        let table = |tag: &[u8; 4]| -> Option<&'static [u8]> {
            let n = u16_at(font, 4)? as usize;
            let r = (0..n).map(|i| 12 + 16 * i).find(|&r| font.get(r..r + 4) == Some(&tag[..]))?;
            font.get(u32_at(font, r + 8)?..u32_at(font, r + 8)? + u32_at(font, r + 12)?)
        };
        let (hhea, hmtx, cmap) = (table(b"hhea")?, table(b"hmtx")?, table(b"cmap")?);
        let height = u16_at(hhea, 4)? as i16 as f64 - u16_at(hhea, 6)? as i16 as f64;
        let n_long = u16_at(hhea, 34)? as usize;
        let mut metrics = Vec::new();
        for g in 0..n_long {
            metrics.push((u16_at(hmtx, 4 * g)? as f64, u16_at(hmtx, 4 * g + 2)? as i16 as f64));
        }
        let last = metrics.last()?.0;
        let mut at = 4 * n_long;
        while let Some(lsb) = u16_at(hmtx, at) {
            metrics.push((last, lsb as i16 as f64));
            at += 2;
        }
        let sub = (0..u16_at(cmap, 2)? as usize).map(|i| 4 + 8 * i).find_map(|r| {
            let (platform, encoding) = (u16_at(cmap, r)?, u16_at(cmap, r + 2)?);
            let off = u32_at(cmap, r + 4)?;
            ((platform == 3 && encoding == 1 || platform == 0) && u16_at(cmap, off)? == 4).then_some(off)
        })?;
        let seg2 = u16_at(cmap, sub + 6)? as usize;
        let mut segments = Vec::new();
        for i in 0..seg2 / 2 {
            let end = u16_at(cmap, sub + 14 + 2 * i)?;
            let start = u16_at(cmap, sub + 16 + seg2 + 2 * i)?;
            let delta = u16_at(cmap, sub + 16 + 2 * seg2 + 2 * i)?;
            let pos = sub + 16 + 3 * seg2 + 2 * i;
            segments.push((end, start, delta, u16_at(cmap, pos)?, pos));
        }
        (height > 0.0).then_some(FontMetrics { height, hmtx: metrics, segments, cmap })
    }

    /// Advance width and left side bearing of the glyph of `c`.
    pub(super) fn glyph(&self, c: char) -> (f64, f64) {
        let code = c as u32;
        let gid = (code <= 0xFFFF)
            .then(|| {
                let code = code as u16;
                let &(_, start, delta, range, pos) = self.segments.iter().find(|s| s.0 >= code)?;
                if code < start {
                    return None;
                }
                if range == 0 {
                    return Some(code.wrapping_add(delta));
                }
                let at = pos + range as usize + 2 * (code - start) as usize;
                let g = u16::from_be_bytes(self.cmap.get(at..at + 2)?.try_into().ok()?);
                (g != 0).then(|| g.wrapping_add(delta))
            })
            .flatten()
            .unwrap_or(0);
        self.hmtx.get(gid as usize).or(self.hmtx.first()).copied().unwrap_or((0.0, 0.0))
    }
}

pub(super) fn rgb(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// An 8-bit RGB PNG of `rgb` (rows from the top), each row with the filter
/// the `png` crate's adaptive heuristic picks.
pub(super) fn encode_png(w: usize, h: usize, rgb: &[u8]) -> Result<Vec<u8>, PictureError> {
    let err = PictureError::Png;
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w as u32, h as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
    let mut writer = enc.write_header().map_err(err)?;
    writer.write_image_data(rgb).map_err(err)?;
    writer.finish().map_err(err)?;
    Ok(out)
}
