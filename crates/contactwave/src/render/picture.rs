//! Raster pictures (the `plot` feature): a field on a uniform pixel grid drawn as a colour
//! map with its axes, a colour bar with units, a title, lines (cracks) and marks
//! (receivers, sources); PNG and animated GIF encoding (`image`). Text is drawn with
//! `ab_glyph` in the DejaVu Sans font the `dejavu` crate embeds (no system font needed).
//! Nothing here knows the physics: the 2D model describes its pictures with [`Heatmap`].

use crate::error::{Error, Result};
use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use image::{Rgb, RgbImage};
use std::sync::OnceLock;

/// Left margin (tick labels of the vertical axis), px.
const LEFT: u32 = 64;
/// Top margin (title and the vertical axis' label), px.
const TOP: u32 = 40;
/// Bottom margin (tick labels and label of the horizontal axis), px.
const BOTTOM: u32 = 48;
/// Colour bar: gap to the field, width, room for its labels, px.
const BAR: (u32, u32, u32) = (16, 16, 80);
/// Text size, px.
const FONT: f32 = 15.0;

/// A field drawn as a colour map.
#[derive(Debug, Clone, Default)]
pub struct Heatmap<'a> {
    /// Columns of the field (one pixel each).
    pub nx: usize,
    /// Rows of the field, the top one first.
    pub nz: usize,
    /// Values, `[row][column]`, in the colour bar's unit.
    pub values: &'a [f64],
    /// Horizontal axis: value at the left and right edges of the field (display units).
    pub x_range: (f64, f64),
    /// Vertical axis: value at the top and bottom edges of the field (display units).
    pub y_range: (f64, f64),
    /// Colour scale: the values drawn with the first and last colour (outside: clipped).
    pub scale: (f64, f64),
    /// A diverging map (blue, white at the middle, red) for signed values; else a
    /// sequential one (viridis).
    pub diverging: bool,
    /// Title above the field.
    pub title: String,
    /// Horizontal axis label with its unit.
    pub xlabel: String,
    /// Vertical axis label with its unit.
    pub ylabel: String,
    /// Colour bar label with its unit.
    pub bar_label: String,
    /// Heights at which a dashed grey line crosses the field (display units), e.g. the
    /// boundaries between layers.
    pub boundaries: Vec<f64>,
    /// Segments drawn over the field (display units), e.g. cracks.
    pub lines: Vec<[(f64, f64); 2]>,
    /// Points marked over the field (display units), e.g. receivers.
    pub marks: Vec<(f64, f64)>,
    /// Segments drawn in a second colour (display units), e.g. transducer apertures.
    pub sources: Vec<[(f64, f64); 2]>,
    /// Named classes with their colours, for a field of class indices (e.g. a contact
    /// state: 0 open, 1 stick, 2 slip): when given, each value is drawn in the colour of
    /// its nearest index (clipped to the classes) and the colour bar is one labelled band
    /// per class instead of a continuous scale; `scale` is then unused.
    pub classes: Vec<(String, [u8; 3])>,
    /// Segments drawn thin in dark grey (display units), e.g. a mesh's outline: its sides,
    /// holes and crack faces.
    pub outline: Vec<[(f64, f64); 2]>,
}

/// The colour of a pixel with no value (NaN: outside a meshed specimen).
pub const NO_VALUE: [u8; 3] = [190, 190, 190];

impl Heatmap<'_> {
    /// The colour of value `v`.
    fn colour_of(&self, v: f64) -> [u8; 3] {
        if v.is_nan() {
            return NO_VALUE;
        }
        if let Some(last) = self.classes.len().checked_sub(1) {
            let k = if v.is_finite() {
                v.round().clamp(0.0, last as f64) as usize
            } else {
                0
            };
            return self.classes[k].1;
        }
        let (lo, hi) = self.scale;
        let span = if hi > lo { hi - lo } else { 1.0 };
        colour((v - lo) / span, self.diverging)
    }
}

fn font() -> &'static FontRef<'static> {
    static FONT_REF: OnceLock<FontRef<'static>> = OnceLock::new();
    // the embedded DejaVu Sans is a valid font: the fallback is never taken
    FONT_REF.get_or_init(|| {
        FontRef::try_from_slice(dejavu::sans::regular())
            .or_else(|_| FontRef::try_from_slice(dejavu::sans_mono::regular()))
            .expect("the embedded DejaVu font parses")
    })
}

/// Width of `s` at `px`, px.
fn text_width(s: &str, px: f32) -> f32 {
    let f = font().as_scaled(PxScale::from(px));
    let mut w = 0.0;
    let mut prev = None;
    for ch in s.chars() {
        let id = f.glyph_id(ch);
        if let Some(p) = prev {
            w += f.kern(p, id);
        }
        w += f.h_advance(id);
        prev = Some(id);
    }
    w
}

/// Draw `s` with its baseline at `y`, its left edge at `x - anchor * width`.
fn text(img: &mut RgbImage, x: f32, y: f32, anchor: f32, s: &str, color: [u8; 3]) {
    let font = font();
    let f = font.as_scaled(PxScale::from(FONT));
    let mut caret = x - anchor * text_width(s, FONT);
    let mut prev = None;
    let (w, h) = img.dimensions();
    for ch in s.chars() {
        let id = f.glyph_id(ch);
        if let Some(p) = prev {
            caret += f.kern(p, id);
        }
        let g = id.with_scale_and_position(PxScale::from(FONT), ab_glyph::point(caret, y));
        caret += f.h_advance(id);
        prev = Some(id);
        if let Some(o) = font.outline_glyph(g) {
            let b = o.px_bounds();
            o.draw(|gx, gy, cov| {
                let (px, py) = (b.min.x as i64 + gx as i64, b.min.y as i64 + gy as i64);
                if px >= 0 && py >= 0 && (px as u32) < w && (py as u32) < h {
                    let p = img.get_pixel_mut(px as u32, py as u32);
                    for (c, t) in p.0.iter_mut().zip(color) {
                        *c = (*c as f32 + (t as f32 - *c as f32) * cov.clamp(0.0, 1.0)).round()
                            as u8;
                    }
                }
            });
        }
    }
}

/// The colour of `t` in [0, 1] (clipped) on the sequential or diverging map.
pub fn colour(t: f64, diverging: bool) -> [u8; 3] {
    const VIRIDIS: [[f64; 3]; 9] = [
        [68.0, 1.0, 84.0],
        [71.0, 44.0, 122.0],
        [59.0, 81.0, 139.0],
        [44.0, 113.0, 142.0],
        [33.0, 144.0, 141.0],
        [39.0, 173.0, 129.0],
        [92.0, 200.0, 99.0],
        [170.0, 220.0, 50.0],
        [253.0, 231.0, 37.0],
    ];
    const RDBU: [[f64; 3]; 7] = [
        [33.0, 102.0, 172.0],
        [103.0, 169.0, 207.0],
        [209.0, 229.0, 240.0],
        [247.0, 247.0, 247.0],
        [253.0, 219.0, 199.0],
        [239.0, 138.0, 98.0],
        [178.0, 24.0, 43.0],
    ];
    let map: &[[f64; 3]] = if diverging { &RDBU } else { &VIRIDIS };
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = t * (map.len() - 1) as f64;
    let i = (s.floor() as usize).min(map.len() - 2);
    let f = s - i as f64;
    let mix = |k: usize| (map[i][k] + (map[i + 1][k] - map[i][k]) * f).round() as u8;
    [mix(0), mix(1), mix(2)]
}

/// A round step near `span / n`: 1, 2 or 5 times a power of ten.
fn nice_step(span: f64, n: f64) -> f64 {
    let raw = (span.abs() / n).max(f64::MIN_POSITIVE);
    let p = 10f64.powf(raw.log10().floor());
    let m = raw / p;
    p * if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    }
}

/// Ticks within [a, b] (either order) at a round step, about `n` of them.
fn ticks(a: f64, b: f64, n: f64) -> Vec<f64> {
    let (lo, hi) = (a.min(b), a.max(b));
    let step = nice_step(hi - lo, n);
    let mut t = (lo / step).ceil() * step;
    let mut out = Vec::new();
    while t <= hi + 1e-9 * step && out.len() < 50 {
        out.push(if t.abs() < 1e-9 * step { 0.0 } else { t });
        t += step;
    }
    out
}

/// A tick label: few digits, no trailing zeros.
fn label(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e4).contains(&a) {
        let s = format!("{v:.2e}");
        // 1.50e-3 -> 1.5e-3
        return match s.split_once('e') {
            Some((m, e)) => {
                let m = m.trim_end_matches('0').trim_end_matches('.');
                format!("{m}e{e}")
            }
            None => s,
        };
    }
    let s = format!("{v:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn put(img: &mut RgbImage, x: i64, y: i64, c: [u8; 3]) {
    let (w, h) = img.dimensions();
    if x >= 0 && y >= 0 && (x as u32) < w && (y as u32) < h {
        img.put_pixel(x as u32, y as u32, Rgb(c));
    }
}

/// A segment `width` px wide (a disc swept along it), clipped to `clip` (x0, y0, x1, y1).
fn segment(img: &mut RgbImage, a: (f64, f64), b: (f64, f64), width: f64, c: [u8; 3]) {
    let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    let steps = (len * 2.0).ceil().max(1.0) as usize;
    let r = 0.5 * width;
    let ri = r.ceil() as i64;
    for s in 0..=steps {
        let f = s as f64 / steps as f64;
        let (x, y) = (a.0 + (b.0 - a.0) * f, a.1 + (b.1 - a.1) * f);
        for dy in -ri..=ri {
            for dx in -ri..=ri {
                let (px, py) = (x.floor() as i64 + dx, y.floor() as i64 + dy);
                let (cx, cy) = (px as f64 + 0.5 - x, py as f64 + 0.5 - y);
                if cx * cx + cy * cy <= r * r {
                    put(img, px, py, c);
                }
            }
        }
    }
}

/// The picture of `h`: the field one pixel per value, axes with ticks, the colour bar.
pub fn heatmap(h: &Heatmap) -> RgbImage {
    let (nx, nz) = (h.nx as u32, h.nz as u32);
    let bar_h = nz.max(120);
    let width = LEFT + nx + BAR.0 + BAR.1 + BAR.2;
    let height = TOP + bar_h + BOTTOM;
    let mut img = RgbImage::from_pixel(width, height, Rgb([255, 255, 255]));
    let (lo, hi) = h.scale;
    let span = if hi > lo { hi - lo } else { 1.0 };
    for iz in 0..nz {
        for ix in 0..nx {
            let v = h.values[(iz * nx + ix) as usize];
            img.put_pixel(LEFT + ix, TOP + iz, Rgb(h.colour_of(v)));
        }
    }
    // display units to pixels (continuous: the field's edges at LEFT, LEFT + nx, ...)
    let (x0, x1) = h.x_range;
    let (y0, y1) = h.y_range;
    let px = |x: f64| LEFT as f64 + (x - x0) / (x1 - x0) * nx as f64;
    let py = |y: f64| TOP as f64 + (y - y0) / (y1 - y0) * nz as f64;
    for &y in &h.boundaries {
        let row = py(y).floor();
        if row >= TOP as f64 && row < (TOP + nz) as f64 {
            // dashes of 6 px, gaps of 4 px
            for ix in (0..nx).filter(|ix| ix % 10 < 6) {
                img.put_pixel(LEFT + ix, row as u32, Rgb([90, 90, 90]));
            }
        }
    }
    for l in &h.outline {
        let (a, b) = ((px(l[0].0), py(l[0].1)), (px(l[1].0), py(l[1].1)));
        segment(&mut img, a, b, 1.5, [60, 60, 60]);
    }
    for l in &h.lines {
        let (a, b) = ((px(l[0].0), py(l[0].1)), (px(l[1].0), py(l[1].1)));
        segment(&mut img, a, b, 5.0, [0, 0, 0]);
        segment(&mut img, a, b, 2.5, [255, 255, 255]);
    }
    for s in &h.sources {
        let (a, b) = ((px(s[0].0), py(s[0].1)), (px(s[1].0), py(s[1].1)));
        segment(&mut img, a, b, 6.0, [230, 0, 180]);
    }
    for &(x, y) in &h.marks {
        let p = (px(x), py(y));
        segment(&mut img, p, p, 10.0, [0, 0, 0]);
        segment(&mut img, p, p, 6.0, [255, 140, 0]);
    }
    // frame
    let black = [0, 0, 0];
    let (l, t, r, b) = (
        LEFT as f64 - 1.0,
        TOP as f64 - 1.0,
        (LEFT + nx) as f64,
        (TOP + nz) as f64,
    );
    for (a, c) in [
        ((l, t), (r, t)),
        ((l, b), (r, b)),
        ((l, t), (l, b)),
        ((r, t), (r, b)),
    ] {
        segment(
            &mut img,
            (a.0 + 0.5, a.1 + 0.5),
            (c.0 + 0.5, c.1 + 0.5),
            1.0,
            black,
        );
    }
    // ticks and labels
    let nxt = (nx as f64 / 90.0).clamp(2.0, 10.0);
    for v in ticks(x0, x1, nxt) {
        let x = px(v);
        segment(&mut img, (x, b + 1.0), (x, b + 6.0), 1.0, black);
        text(&mut img, x as f32, b as f32 + 21.0, 0.5, &label(v), black);
    }
    let nzt = (nz as f64 / 45.0).clamp(2.0, 8.0);
    for v in ticks(y0, y1, nzt) {
        let y = py(v);
        segment(&mut img, (l - 5.0, y), (l, y), 1.0, black);
        text(
            &mut img,
            l as f32 - 8.0,
            y as f32 + 5.0,
            1.0,
            &label(v),
            black,
        );
    }
    text(
        &mut img,
        (LEFT + nx / 2) as f32,
        (height - 8) as f32,
        0.5,
        &h.xlabel,
        black,
    );
    text(&mut img, 6.0, TOP as f32 - 10.0, 0.0, &h.ylabel, black);
    text(
        &mut img,
        (LEFT + nx / 2) as f32,
        TOP as f32 - 14.0,
        0.5,
        &h.title,
        black,
    );
    // the colour bar: the top is the scale's high end (the last class)
    let bx = LEFT + nx + BAR.0;
    let n_classes = h.classes.len();
    for j in 0..bar_h {
        let f = 1.0 - (j as f64 + 0.5) / bar_h as f64;
        let c = if n_classes > 0 {
            h.classes[((f * n_classes as f64) as usize).min(n_classes - 1)].1
        } else {
            colour(f, h.diverging)
        };
        for i in 0..BAR.1 {
            img.put_pixel(bx + i, TOP + j, Rgb(c));
        }
    }
    let (bl, br) = (bx as f64 - 0.5, (bx + BAR.1) as f64 - 0.5);
    let (bt, bb) = (TOP as f64 - 0.5, (TOP + bar_h) as f64 - 0.5);
    for (a, c) in [
        ((bl, bt), (br, bt)),
        ((bl, bb), (br, bb)),
        ((bl, bt), (bl, bb)),
        ((br, bt), (br, bb)),
    ] {
        segment(&mut img, a, c, 1.0, black);
    }
    let by = |v: f64| TOP as f64 + (1.0 - (v - lo) / span) * bar_h as f64;
    // a continuous bar's ticks at round values, a class bar's names at its bands' middles
    let marks: Vec<(f64, String)> = if n_classes > 0 {
        let band = bar_h as f64 / n_classes as f64;
        let top = TOP as f64 + bar_h as f64;
        (h.classes.iter().enumerate())
            .map(|(k, (name, _))| (top - (k as f64 + 0.5) * band, name.clone()))
            .collect()
    } else {
        ticks(lo, hi, (bar_h as f64 / 40.0).clamp(2.0, 6.0))
            .into_iter()
            .map(|v| (by(v), label(v)))
            .collect()
    };
    for (y, name) in marks {
        segment(&mut img, (br, y), (br + 5.0, y), 1.0, black);
        text(&mut img, br as f32 + 8.0, y as f32 + 5.0, 0.0, &name, black);
    }
    text(
        &mut img,
        (bx + BAR.1 / 2) as f32,
        TOP as f32 - 10.0,
        0.5,
        &h.bar_label,
        black,
    );
    img
}

fn encode_error(name: &str, e: impl std::fmt::Display) -> Error {
    crate::render::svg::plot_error(name, e.to_string().into())
}

/// The PNG file of `img`.
pub fn png(name: &str, img: &RgbImage) -> Result<Vec<u8>> {
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| encode_error(name, e))?;
    Ok(out.into_inner())
}

/// An animated GIF of `frames` (all of one size), `delay_ms` each, looping forever.
pub fn gif(name: &str, frames: &[RgbImage], delay_ms: u32) -> Result<Vec<u8>> {
    use image::codecs::gif::{GifEncoder, Repeat};
    let mut out = Vec::new();
    {
        // speed 10: NeuQuant samples a tenth of the pixels for each frame's palette
        let mut enc = GifEncoder::new_with_speed(&mut out, 10);
        enc.set_repeat(Repeat::Infinite)
            .map_err(|e| encode_error(name, e))?;
        for f in frames {
            let rgba = image::DynamicImage::ImageRgb8(f.clone()).into_rgba8();
            let frame = image::Frame::from_parts(
                rgba,
                0,
                0,
                image::Delay::from_numer_denom_ms(delay_ms, 1),
            );
            enc.encode_frame(frame).map_err(|e| encode_error(name, e))?;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        assert_eq!(ticks(0.0, 40.0, 5.0), [0.0, 10.0, 20.0, 30.0, 40.0]);
        assert_eq!(ticks(10.0, 0.0, 4.0), [0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        assert_eq!(label(1.5e-3), "0.0015");
        assert_eq!(label(2.5e-5), "2.5e-5");
        assert_eq!(label(12.0), "12");
        // the maps' ends
        assert_eq!(colour(0.0, false), [68, 1, 84]);
        assert_eq!(colour(0.5, true), [247, 247, 247]);
        assert_eq!(colour(7.0, true), [178, 24, 43]);
    }

    /// A layer boundary is a dashed grey line across the field at its height, over the
    /// field's colours and nowhere else.
    #[test]
    fn a_boundary_is_a_dashed_line_at_its_height() {
        let values = vec![0.5; 100 * 50];
        let h = Heatmap {
            nx: 100,
            nz: 50,
            values: &values,
            x_range: (0.0, 10.0),
            y_range: (0.0, 5.0),
            scale: (0.0, 1.0),
            boundaries: vec![2.0],
            ..Default::default()
        };
        let img = heatmap(&h);
        let grey = |row: u32| {
            (0..100)
                .filter(|&ix| img.get_pixel(LEFT + ix, TOP + row).0 == [90, 90, 90])
                .count()
        };
        // 2 of 5 units: row 20; 6 px of every 10
        assert_eq!(grey(20), 60);
        assert_eq!(grey(19) + grey(21) + grey(0) + grey(49), 0);
    }
}
