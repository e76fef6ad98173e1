//! The stereonet of a scene's joints (`stereonet.png`): every
//! `[[joint_sets]]` and `[[joints]]` entry of a 3D scene as its pole and its
//! great circle on a lower-hemisphere equal-area (Schmidt) net, north up,
//! labelled by name with dip / dip direction. The first plot a rock
//! engineer draws of a rock mass: which sets are steep, which dip together
//! and where their intersections plunge.
//!
//! Projection (Priest, Hemispherical Projection Methods in Rock Mechanics):
//! a downward unit vector v = (e, n, u), u <= 0 (x east, y north, z up),
//! plots at R (e, n) / sqrt(1 - u): at the distance R sqrt(2) sin(θ / 2)
//! from the centre, θ its angle from the vertical, in the direction of its
//! trend. A plane's pole is its downward normal (trend dip direction + 180,
//! plunge 90 - dip); its great circle is the projection of its downward
//! lines.

use plotters::style::text_anchor::{HPos, VPos};

use super::colours::INK;
use super::picture_error::PictureError;
use super::raster::{encode_png, label, register_font, Canvas, Label};
use crate::mesh::joints::{geometry, JointSpec, Orientation, Placement};

/// The picture's file name when the scene has joints by dip and dip
/// direction (a 3D scene's `[[joint_sets]]` or `[[joints]]`).
pub fn stereonet_file(joints: &[JointSpec]) -> Option<&'static str> {
    joints.iter().any(|j| matches!(j.orientation, Orientation::Dip { .. })).then_some("stereonet.png")
}

/// Canvas size, the net's centre and radius (pixels).
const W: usize = 1000;
const H: usize = 1000;
const CX: f64 = 430.0;
const CY: f64 = 540.0;
const R: f64 = 360.0;

/// A colour per joint, in turn.
const COLOURS: [[u8; 3]; 8] = [
    [214, 39, 40],
    [31, 119, 180],
    [44, 160, 44],
    [148, 103, 189],
    [255, 127, 14],
    [23, 190, 207],
    [140, 86, 75],
    [227, 119, 194],
];
const NET: [u8; 3] = [205, 205, 205];

/// Where the downward direction `v` plots on a net of radius 1: (east,
/// north). An upward `v` is turned down (a line has no sense).
pub(super) fn plot(v: [f64; 3]) -> [f64; 2] {
    let v = if v[2] > 0.0 { v.map(|c| -c) } else { v };
    let s = (1.0 - v[2]).max(1e-300).sqrt();
    [v[0] / s, v[1] / s]
}

/// The pole of the plane of `dip` and `dip_direction` (degrees) on a net
/// of radius 1: its downward normal.
pub(super) fn pole(dip: f64, dip_direction: f64) -> [f64; 2] {
    let n = geometry::normal_3d(dip, dip_direction);
    plot(n.map(|c| -c))
}

/// The great circle of the plane on a net of radius 1, from one end of its
/// strike to the other through the dip vector, in `k` + 1 points.
pub(super) fn great_circle(dip: f64, dip_direction: f64, k: usize) -> Vec<[f64; 2]> {
    let (d, a) = (dip.to_radians(), dip_direction.to_radians());
    let strike = [-a.cos(), a.sin(), 0.0];
    let down = [d.cos() * a.sin(), d.cos() * a.cos(), -d.sin()];
    (0..=k)
        .map(|i| {
            let t = std::f64::consts::PI * i as f64 / k as f64;
            let (c, s) = (t.cos(), t.sin());
            plot([c * strike[0] + s * down[0], c * strike[1] + s * down[1], c * strike[2] + s * down[2]])
        })
        .collect()
}

/// A point of the unit net on the canvas.
fn screen(p: [f64; 2]) -> [f32; 2] {
    [(CX + R * p[0]) as f32, (CY - R * p[1]) as f32]
}

/// The net: great circles striking north every 10 degrees of dip, small
/// circles about the north-south axis every 10 degrees, the primitive and
/// the compass points.
fn net(cv: &mut Canvas, labels: &mut Vec<Label>) {
    for step in 1..18 {
        let angle = 10.0 * step as f64;
        let (dip, dd) = if angle <= 90.0 { (angle, 90.0) } else { (180.0 - angle, 270.0) };
        cv.polyline(great_circle(dip, dd, 90).into_iter().map(screen), 1.0, NET, 1.0);
        // the lines at `angle` from north
        let phi = angle.to_radians();
        let small = (0..=90).map(|i| {
            let psi = std::f64::consts::PI * i as f64 / 90.0;
            screen(plot([phi.sin() * psi.cos(), phi.cos(), -phi.sin() * psi.sin()]))
        });
        cv.polyline(small, 1.0, NET, 1.0);
    }
    let rim = (0..=360).map(|i| {
        let t = (i as f64).to_radians();
        screen([t.sin(), t.cos()])
    });
    cv.polyline(rim, 2.0, INK, 1.0);
    cv.segment(screen([-0.02, 0.0]), screen([0.02, 0.0]), 1.5, INK, 1.0, false);
    cv.segment(screen([0.0, -0.02]), screen([0.0, 0.02]), 1.5, INK, 1.0, false);
    for (text, at) in [("N", [0.0, 1.06]), ("E", [1.06, 0.0]), ("S", [0.0, -1.06]), ("W", [-1.06, 0.0])] {
        let p = screen(at);
        labels.push(label(text, (p[0] as f64, p[1] as f64), 20.0, (HPos::Center, VPos::Center)));
    }
}

/// The stereonet of the joints given by dip and dip direction (joints by
/// a 2D trace angle are left out). A dip or dip direction that is not a
/// number is an error; others are drawn as the projection takes them.
pub fn stereonet_png(title: &str, joints: &[JointSpec]) -> Result<Vec<u8>, PictureError> {
    register_font();
    let mut planes = Vec::new();
    for j in joints {
        if let Orientation::Dip { dip, dip_direction } = j.orientation {
            if !(dip.is_finite() && dip_direction.is_finite()) {
                return Err(PictureError::Empty(format!("{} has dip {dip} / dip direction {dip_direction}", j.key)));
            }
            planes.push((j, dip, dip_direction));
        }
    }
    if planes.is_empty() {
        return Err(PictureError::Empty("no joint is given by dip and dip direction".into()));
    }
    let mut cv = Canvas::new(W, H);
    let mut labels = Vec::new();
    net(&mut cv, &mut labels);
    for (i, (j, dip, dd)) in planes.iter().enumerate() {
        let c = COLOURS[i % COLOURS.len()];
        cv.polyline(great_circle(*dip, *dd, 180).into_iter().map(screen), 2.5, c, 1.0);
        let p = screen(pole(*dip, *dd));
        cv.dot(p, 7.0, [0, 0, 0]);
        cv.dot(p, 5.5, c);
        labels.push(label(j.name.clone(), (p[0] as f64 + 10.0, p[1] as f64 - 10.0), 15.0, (HPos::Left, VPos::Bottom)));
        // the legend: name, dip / dip direction, spacing or point
        let y = 150.0 + 28.0 * i as f64;
        if y > H as f64 - 20.0 {
            continue;
        }
        cv.rect(820.0, y - 7.0, 840.0, y + 7.0, c);
        let how = match j.placement {
            Placement::Set { spacing, .. } => format!("s = {}", crate::mesh::joints::trim(spacing)),
            Placement::Single { .. } => "single".to_string(),
        };
        let text = format!("{} {} ({how})", j.name, j.orientation.label());
        labels.push(label(text, (848.0, y), 14.0, (HPos::Left, VPos::Center)));
    }
    labels.push(label(title, (24.0, 14.0), 24.0, (HPos::Left, VPos::Top)));
    labels.push(label(
        "the joints: poles (dots) and great circles, lower hemisphere, equal area (Schmidt net, 10° grid)",
        (24.0, 50.0),
        16.0,
        (HPos::Left, VPos::Top),
    ));
    labels.push(label("name dip/dip direction", (820.0, 120.0), 14.0, (HPos::Left, VPos::Center)));
    cv.text(&labels)?;
    encode_png(cv.w, cv.h, &cv.rgb)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        (a[0] - b[0]).abs() < tol && (a[1] - b[1]).abs() < tol
    }

    fn set(name: &str, dip: f64, dip_direction: f64) -> JointSpec {
        JointSpec {
            key: format!("joint_sets[{name}]"),
            name: name.into(),
            orientation: Orientation::Dip { dip, dip_direction },
            placement: Placement::Set { spacing: 2.0, offset: 0.0 },
            bodies: vec!["rock".into()],
            persistence: None,
            extent: None,
            snap: 0.0,
        }
    }

    #[test]
    fn poles_plot_where_the_schmidt_net_puts_them() {
        // a horizontal joint's pole is vertical: the centre
        assert!(close(pole(0.0, 123.0), [0.0, 0.0], 1e-12));
        // a vertical joint's pole is horizontal: the rim, at dd + 180
        for dd in [0.0f64, 30.0, 135.0, 270.0, 359.0] {
            let az = (dd + 180.0f64).to_radians();
            assert!(close(pole(90.0, dd), [az.sin(), az.cos()], 1e-12), "dd {dd}: {:?}", pole(90.0, dd));
        }
        // dip 60 / 030: plunge 30 towards 210, r = sqrt(2) sin(60° / 2) = sqrt(1 - sin 30°)
        let r = 2f64.sqrt() * 30f64.to_radians().sin();
        let az = 210f64.to_radians();
        assert!(close(pole(60.0, 30.0), [r * az.sin(), r * az.cos()], 1e-12));
        assert!((r - 0.5f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn great_circles_are_the_planes_lines() {
        // horizontal: the primitive; vertical: the diameter along the strike
        for p in great_circle(0.0, 40.0, 36) {
            assert!(((p[0].hypot(p[1])) - 1.0).abs() < 1e-12);
        }
        let v = great_circle(90.0, 90.0, 36);
        assert!(close(v[0], [0.0, 1.0], 1e-12) && close(v[18], [0.0, 0.0], 1e-12) && close(v[36], [0.0, -1.0], 1e-12));
        // the middle point is the dip vector: plunge = dip, trend = dip direction
        let (dip, dd) = (50.0f64, 200.0f64);
        let mid = great_circle(dip, dd, 36)[18];
        let r = 2f64.sqrt() * ((90.0 - dip) / 2.0).to_radians().sin();
        assert!(close(mid, [r * dd.to_radians().sin(), r * dd.to_radians().cos()], 1e-12));
        // every point is 90° from the pole: its direction is normal to n
        let n = geometry::normal_3d(dip, dd);
        for p in great_circle(dip, dd, 36) {
            let r2 = p[0] * p[0] + p[1] * p[1];
            // invert the projection: u = r² - 1, (e, n) = p sqrt(1 - u)
            let u = r2 - 1.0;
            let s = (1.0 - u).sqrt();
            let v = [p[0] * s, p[1] * s, u];
            assert!((v[0] * n[0] + v[1] * n[1] + v[2] * n[2]).abs() < 1e-12);
        }
    }

    #[test]
    fn stereonet_is_drawn_for_sets_and_not_for_bad_ones() {
        let sets = [set("J1", 60.0, 30.0), set("J2", 80.0, 150.0), set("J3", 10.0, 270.0)];
        assert_eq!(stereonet_file(&sets), Some("stereonet.png"));
        let png = stereonet_png("three sets", &sets).expect("drawn");
        let mut reader = png::Decoder::new(png.as_slice()).read_info().expect("a PNG");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("pixels");
        assert_eq!((info.width as usize, info.height as usize), (W, H));
        // J1's pole is painted in its colour
        let p = screen(pole(60.0, 30.0));
        let i = (p[1] as usize * W + p[0] as usize) * 3;
        assert_eq!(&buf[i..i + 3], &COLOURS[0], "J1's pole at {p:?}");
        std::fs::write(std::env::temp_dir().join("subcontact_stereonet.png"), &png).ok();
        // bad sets: an error or a picture, never a panic
        assert!(stereonet_png("nan", &[set("J", f64::NAN, 30.0)]).is_err());
        assert!(stereonet_png("inf", &[set("J", 45.0, f64::INFINITY)]).is_err());
        assert!(stereonet_png("odd", &[set("J", 120.0, -30.0), set("K", -5.0, 720.0)]).is_ok());
        let mut flat = set("T", 0.0, 0.0);
        flat.orientation = Orientation::Angle(30.0);
        assert_eq!(stereonet_file(std::slice::from_ref(&flat)), None);
        assert!(stereonet_png("2d", &[flat]).is_err());
        assert!(stereonet_png("none", &[]).is_err());
    }
}
