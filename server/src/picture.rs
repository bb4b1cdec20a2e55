//! Pictures of a toolpath: SVG (isometric view plus top/front/side views), and
//! PNG as that SVG rasterised by resvg, so both show the same drawing.

use std::fmt::Write as _;
use std::path::Path;

use resvg::tiny_skia;
use resvg::usvg::{self, fontdb};

use runtime::dryrun::{DryRun, Toolpath, ToolpathSegment};

/// A view: projects a 3D point to 2D (x right, y up).
#[derive(Clone, Copy)]
enum View {
    Iso,
    Top,
    Front,
    Side,
}

impl View {
    fn project(self, p: [f64; 3]) -> (f64, f64) {
        match self {
            View::Top => (p[0], p[1]),
            View::Front => (p[0], p[2]),
            View::Side => (p[1], p[2]),
            View::Iso => {
                // Standard isometric: X to the lower right, Y to the upper right, Z up.
                let c = std::f64::consts::FRAC_PI_6.cos();
                let s = std::f64::consts::FRAC_PI_6.sin();
                ((p[0] - p[1]) * c, (p[0] + p[1]) * s + p[2])
            }
        }
    }

    fn name(self) -> &'static str {
        match self {
            View::Iso => "isometric",
            View::Top => "top (XY)",
            View::Front => "front (XZ)",
            View::Side => "side (YZ)",
        }
    }
}

/// Colour for a feed on a blue → green → yellow → red ramp.
fn feed_colour(feed: f64, min: f64, max: f64) -> (u8, u8, u8) {
    let t = if max > min {
        ((feed - min) / (max - min)).clamp(0.0, 1.0)
    } else {
        0.5
    };
    let stops = [
        (0.0, (49, 54, 149)),
        (0.33, (38, 166, 91)),
        (0.66, (230, 200, 30)),
        (1.0, (215, 48, 39)),
    ];
    for w in stops.windows(2) {
        let (t0, c0) = w[0];
        let (t1, c1) = w[1];
        if t <= t1 {
            let f = (t - t0) / (t1 - t0);
            let lerp = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * f).round() as u8;
            return (lerp(c0.0, c1.0), lerp(c0.1, c1.1), lerp(c0.2, c1.2));
        }
    }
    (215, 48, 39)
}

fn feed_range(tp: &Toolpath) -> (f64, f64) {
    let feeds = tp
        .segments
        .iter()
        .filter(|s| s.kind != "rapid" && s.feed.is_finite())
        .map(|s| s.feed);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for f in feeds {
        lo = lo.min(f);
        hi = hi.max(f);
    }
    if lo.is_finite() {
        (lo, hi)
    } else {
        (0.0, 1.0)
    }
}

/// 2D bounds of the toolpath in a view.
fn bounds(tp: &Toolpath, view: View) -> (f64, f64, f64, f64) {
    let (mut x0, mut y0, mut x1, mut y1) = (
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    );
    for s in &tp.segments {
        for p in &s.points {
            let (x, y) = view.project(*p);
            if x.is_finite() && y.is_finite() {
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
    }
    if !x0.is_finite() {
        return (0.0, 0.0, 1.0, 1.0);
    }
    (x0, y0, x1.max(x0 + 1e-6), y1.max(y0 + 1e-6))
}

/// Maps a view into a box `(left, top, width, height)` in picture pixels.
struct Frame {
    view: View,
    scale: f64,
    ox: f64,
    oy: f64,
}

impl Frame {
    fn new(tp: &Toolpath, view: View, bx: (f64, f64, f64, f64)) -> Frame {
        let (x0, y0, x1, y1) = bounds(tp, view);
        let pad = 12.0;
        let sx = (bx.2 - 2.0 * pad) / (x1 - x0);
        let sy = (bx.3 - 2.0 * pad) / (y1 - y0);
        let scale = sx.min(sy);
        let used_w = (x1 - x0) * scale;
        let used_h = (y1 - y0) * scale;
        let ox = bx.0 + pad + (bx.2 - 2.0 * pad - used_w) / 2.0 - x0 * scale;
        let oy = bx.1 + pad + (bx.3 - 2.0 * pad - used_h) / 2.0 + y1 * scale;
        Frame {
            view,
            scale,
            ox,
            oy,
        }
    }

    fn map(&self, p: [f64; 3]) -> (f64, f64) {
        let (x, y) = self.view.project(p);
        (self.ox + x * self.scale, self.oy - y * self.scale)
    }
}

/// Layout: a large isometric view on the left, three orthographic views stacked on the right.
/// A box in picture pixels: left, top, width, height.
type Rect = (f64, f64, f64, f64);

fn layout() -> (f64, f64, Vec<(View, Rect)>) {
    let (w, h) = (1200.0, 800.0);
    let top = 50.0;
    let main = (0.0, top, 800.0, h - top - 40.0);
    let side_h = (h - top - 40.0) / 3.0;
    let views = vec![
        (View::Iso, main),
        (View::Top, (800.0, top, 400.0, side_h)),
        (View::Front, (800.0, top + side_h, 400.0, side_h)),
        (View::Side, (800.0, top + 2.0 * side_h, 400.0, side_h)),
    ];
    (w, h, views)
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The attributes of `seg`'s polyline after its points, closing the element: rapids
/// dashed, feed moves coloured by their feed within `feeds` and tagged with their line.
fn style(seg: &ToolpathSegment, feeds: (f64, f64)) -> String {
    if seg.kind == "rapid" {
        return r##"" fill="none" stroke="#e04040" stroke-width="0.8" stroke-dasharray="4 3" opacity="0.7"/>"##.to_string() + "\n";
    }
    let (r, g, b) = feed_colour(seg.feed, feeds.0, feeds.1);
    format!(
        "\" fill=\"none\" stroke=\"rgb({r},{g},{b})\" stroke-width=\"1.2\" data-line=\"{}\"/>\n",
        seg.line + 1
    )
}

/// Characters `format!("{x:.2}")` takes at most (rounding may carry into a new digit).
fn fixed2_len(x: f64) -> u64 {
    let int = (x.abs() + 0.005).floor();
    let mut digits = 1;
    let mut p = 10.0;
    while int >= p {
        digits += 1;
        p *= 10.0;
    }
    u64::from(x.is_sign_negative()) + digits + 3
}

/// The points of `seg` in the view of `f` that can be drawn.
fn screen_points<'a>(
    seg: &'a ToolpathSegment,
    f: &'a Frame,
) -> impl Iterator<Item = (f64, f64)> + 'a {
    seg.points
        .iter()
        .map(|p| f.map(*p))
        .filter(|(x, y)| x.is_finite() && y.is_finite())
}

/// Bytes at most that [`polyline`] appends for `seg` in the view of `f`, with
/// `style` its [`style`].
fn polyline_len(seg: &ToolpathSegment, f: &Frame, style: &str) -> u64 {
    let (mut len, mut n) = (0u64, 0u64);
    for (x, y) in screen_points(seg, f) {
        len += fixed2_len(x) + 1 + fixed2_len(y) + 1;
        n += 1;
    }
    if n < 2 {
        return 0;
    }
    r#"<polyline points=""#.len() as u64 + len - 1 + style.len() as u64
}

/// Appends the polyline of `seg` in the view of `f`, closed by `style`; nothing for a
/// segment with fewer than two points that can be drawn.
fn polyline(s: &mut String, seg: &ToolpathSegment, f: &Frame, style: &str) {
    if screen_points(seg, f).nth(1).is_none() {
        return;
    }
    s.push_str(r#"<polyline points=""#);
    for (i, (x, y)) in screen_points(seg, f).enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{x:.2},{y:.2}");
    }
    s.push_str(style);
}

/// Largest SVG written by default, in MB: beyond it the picture is cut off, see
/// [`svg`].
pub const DEFAULT_MAX_SVG_MB: u64 = 32;

/// Writes the SVG picture of `tp` to `out` as it is made. It stops drawing
/// before `max_bytes`; when the toolpath needs more, the picture says so and the
/// result is the first segment left out: its (0-based) line and its file.
pub fn svg(
    out: &mut impl std::io::Write,
    tp: &Toolpath,
    title: &str,
    dry: &DryRun,
    max_bytes: u64,
) -> std::io::Result<Option<(u32, u32)>> {
    let (w, h, views) = layout();
    let (fmin, fmax) = feed_range(tp);
    let mut s = String::new();
    // The legend after the toolpath takes under 8 KB.
    let budget = max_bytes.saturating_sub(8192);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif">"#
    );
    let _ = writeln!(s, r##"<rect width="100%" height="100%" fill="#fafafa"/>"##);
    let t = &dry.totals;
    let _ = writeln!(
        s,
        r##"<text x="16" y="30" font-size="18" fill="#222">{} — cycle {:.1} s (cutting {:.1} s, rapid {:.1} s), {:.0} mm</text>"##,
        esc(title),
        t.cycle_time_s,
        t.cutting_s,
        t.rapid_s,
        t.distance_mm
    );
    let frames: Vec<(View, Rect, Frame)> = views
        .into_iter()
        .map(|(view, bx)| (view, bx, Frame::new(tp, view, bx)))
        .collect();
    // Every view draws the same segments: as many, from the first, as fit in all views
    // together (each view's frame and name take under 300 bytes).
    let mut size = (s.len() + 300 * frames.len()) as u64;
    let mut limit = tp.segments.len();
    for (i, seg) in tp.segments.iter().enumerate() {
        let style = style(seg, (fmin, fmax));
        size += frames
            .iter()
            .map(|(_, _, f)| polyline_len(seg, f, &style))
            .sum::<u64>();
        if size > budget {
            limit = i;
            break;
        }
    }
    for (view, bx, f) in &frames {
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#ddd"/>"##,
            bx.0 + 2.0,
            bx.1,
            bx.2 - 4.0,
            bx.3 - 2.0
        );
        let _ = writeln!(
            s,
            r##"<text x="{}" y="{}" font-size="12" fill="#666">{}</text>"##,
            bx.0 + 8.0,
            bx.1 + 14.0,
            view.name()
        );
        for seg in &tp.segments[..limit] {
            if s.len() > 1 << 16 {
                out.write_all(s.as_bytes())?;
                s.clear();
            }
            polyline(&mut s, seg, f, &style(seg, (fmin, fmax)));
        }
    }
    // The first segment left out.
    let cut = tp.segments.get(limit).map(|seg| (seg.line, seg.file));
    // Legend: rapids and the feed colour ramp.
    let ly = h - 22.0;
    let _ = writeln!(
        s,
        r##"<line x1="16" y1="{ly}" x2="56" y2="{ly}" stroke="#e04040" stroke-dasharray="4 3"/><text x="62" y="{}" font-size="12" fill="#333">rapid</text>"##,
        ly + 4.0
    );
    for i in 0..40 {
        let f = fmin + (fmax - fmin) * i as f64 / 39.0;
        let (r, g, b) = feed_colour(f, fmin, fmax);
        let _ = writeln!(
            s,
            r#"<rect x="{}" y="{}" width="4" height="10" fill="rgb({r},{g},{b})"/>"#,
            140.0 + i as f64 * 4.0,
            ly - 5.0
        );
    }
    let _ = writeln!(
        s,
        r##"<text x="310" y="{}" font-size="12" fill="#333">feed {:.0} – {:.0} mm/min</text>"##,
        ly + 4.0,
        fmin,
        fmax
    );
    if let Some((line, _)) = cut {
        let _ = writeln!(
            s,
            r##"<text x="16" y="52" font-size="14" fill="#c00">toolpath cut off at line {} to keep the file under {} MB (raise with --max-svg-mb)</text>"##,
            line + 1,
            max_bytes >> 20
        );
    }
    s.push_str("</svg>\n");
    out.write_all(s.as_bytes())?;
    Ok(cut)
}

/// Families tried, in order, for the picture's `sans-serif` text; the first
/// installed one is used, else any installed family.
const SANS_SERIF: &[&str] = &[
    "DejaVu Sans",
    "Liberation Sans",
    "Noto Sans",
    "Arial",
    "Helvetica",
    "FreeSans",
];

/// The system's fonts (the folders fontdb searches: fontconfig's on Linux),
/// with `sans-serif` mapped to an installed family. `None` when no font is
/// installed.
fn system_fonts() -> Option<fontdb::Database> {
    let mut db = fontdb::Database::new();
    db.load_system_fonts();
    let installed = |name: &str| {
        db.faces()
            .any(|f| f.families.iter().any(|(family, _)| family == name))
    };
    let family = match SANS_SERIF.iter().find(|name| installed(name)) {
        Some(name) => name.to_string(),
        None => db.faces().next()?.families.first()?.0.clone(),
    };
    db.set_sans_serif_family(family);
    Some(db)
}

/// Rasterises an SVG picture made by [`svg`] into a PNG file at its own size,
/// text included when the system has a font. Returns whether it had one.
pub fn png(svg: &[u8], path: &Path) -> Result<bool, String> {
    let fonts = system_fonts();
    let has_fonts = fonts.is_some();
    let options = usvg::Options {
        fontdb: std::sync::Arc::new(fonts.unwrap_or_default()),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_data(svg, &options).map_err(|e| e.to_string())?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        tiny_skia::Pixmap::new(size.width(), size.height()).ok_or("cannot allocate the picture")?;
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    pixmap.save_png(path).map_err(|e| e.to_string())?;
    Ok(has_fonts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed2_len_bounds_the_formatted_length() {
        for x in [
            0.0, -0.0, 0.004, -0.001, 9.994, 9.995, 9.996, 99.999, 100.0, -123.456, 1e6, 1e15,
            -9999.995, 0.5, 1e-9,
        ] {
            let real = format!("{x:.2}").len() as u64;
            let bound = fixed2_len(x);
            assert!(real <= bound && bound <= real + 1, "{x}: {real} vs {bound}");
        }
    }

    #[test]
    fn polyline_len_bounds_the_polyline() {
        let tp = Toolpath {
            segments: vec![ToolpathSegment {
                kind: "feed",
                line: 41,
                file: 0,
                feed: 800.0,
                tool: 1,
                points: vec![[0.0, 0.0, 0.0], [-12.345, 99.999, 3.0], [1e4, 5.0, -7.0]],
            }],
            ..Toolpath::default()
        };
        for (view, bx) in layout().2 {
            let f = Frame::new(&tp, view, bx);
            let seg = &tp.segments[0];
            let style = style(seg, (100.0, 1000.0));
            let mut s = String::new();
            polyline(&mut s, seg, &f, &style);
            let bound = polyline_len(seg, &f, &style);
            assert!(s.ends_with("data-line=\"42\"/>\n"), "{s}");
            assert!(
                s.len() as u64 <= bound && bound <= s.len() as u64 + 6,
                "{s}: {bound}"
            );
        }
    }
}
