//! What an audience sees change: the share of pixels whose colour changes by a CIEDE2000
//! difference of at least [`VISIBLE_DELTA_E`] between two pictures (Sharma, Wu & Dalal 2005,
//! "The CIEDE2000 color-difference formula: implementation notes"), sRGB pixels read as D65 Lab.

use image::RgbaImage;

/// The colour difference a person sees at once: ΔE₀₀ ≈ 1 is the just-noticeable difference
/// side by side; 5 is plain at a glance.
pub const VISIBLE_DELTA_E: f32 = 5.0;

/// CIE L*a*b* (D65) of an 8-bit sRGB colour.
pub fn lab([r, g, b]: [u8; 3]) -> [f64; 3] {
    let linear = |c: u8| {
        let c = f64::from(c) / 255.0;
        if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
    };
    let (r, g, b) = (linear(r), linear(g), linear(b));
    let x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
    let y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    let z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
    let f = |t: f64| if t > 216.0 / 24389.0 { t.cbrt() } else { (24389.0 / 27.0 * t + 16.0) / 116.0 };
    let (fx, fy, fz) = (f(x), f(y), f(z));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// CIEDE2000 colour difference of two L*a*b* colours (kL = kC = kH = 1).
pub fn delta_e_2000([l1, a1, b1]: [f64; 3], [l2, a2, b2]: [f64; 3]) -> f64 {
    let c_bar = ((a1 * a1 + b1 * b1).sqrt() + (a2 * a2 + b2 * b2).sqrt()) / 2.0;
    let g = 0.5 * (1.0 - (c_bar.powi(7) / (c_bar.powi(7) + 25f64.powi(7))).sqrt());
    let (a1p, a2p) = ((1.0 + g) * a1, (1.0 + g) * a2);
    let (c1p, c2p) = ((a1p * a1p + b1 * b1).sqrt(), (a2p * a2p + b2 * b2).sqrt());
    let hue = |b: f64, a: f64| if b == 0.0 && a == 0.0 { 0.0 } else { b.atan2(a).to_degrees().rem_euclid(360.0) };
    let (h1p, h2p) = (hue(b1, a1p), hue(b2, a2p));
    let dlp = l2 - l1;
    let dcp = c2p - c1p;
    let dhp = if c1p * c2p == 0.0 {
        0.0
    } else if (h2p - h1p).abs() <= 180.0 {
        h2p - h1p
    } else if h2p - h1p > 180.0 {
        h2p - h1p - 360.0
    } else {
        h2p - h1p + 360.0
    };
    let d_hp = 2.0 * (c1p * c2p).sqrt() * (dhp / 2.0).to_radians().sin();
    let lp_bar = (l1 + l2) / 2.0;
    let cp_bar = (c1p + c2p) / 2.0;
    let hp_bar = if c1p * c2p == 0.0 {
        h1p + h2p
    } else if (h1p - h2p).abs() <= 180.0 {
        (h1p + h2p) / 2.0
    } else if h1p + h2p < 360.0 {
        (h1p + h2p + 360.0) / 2.0
    } else {
        (h1p + h2p - 360.0) / 2.0
    };
    let t = 1.0 - 0.17 * (hp_bar - 30.0).to_radians().cos()
        + 0.24 * (2.0 * hp_bar).to_radians().cos()
        + 0.32 * (3.0 * hp_bar + 6.0).to_radians().cos()
        - 0.20 * (4.0 * hp_bar - 63.0).to_radians().cos();
    let d_theta = 30.0 * (-((hp_bar - 275.0) / 25.0).powi(2)).exp();
    let r_c = 2.0 * (cp_bar.powi(7) / (cp_bar.powi(7) + 25f64.powi(7))).sqrt();
    let s_l = 1.0 + 0.015 * (lp_bar - 50.0).powi(2) / (20.0 + (lp_bar - 50.0).powi(2)).sqrt();
    let s_c = 1.0 + 0.045 * cp_bar;
    let s_h = 1.0 + 0.015 * cp_bar * t;
    let r_t = -(2.0 * d_theta).to_radians().sin() * r_c;
    let (l, c, h) = (dlp / s_l, dcp / s_c, d_hp / s_h);
    (l * l + c * c + h * h + r_t * c * h).sqrt()
}

/// The share of pixels, percent, whose colour differs by at least [`VISIBLE_DELTA_E`] between
/// `a` and `b` (images of one size; 100 when the sizes differ).
pub fn visible_percent(a: &RgbaImage, b: &RgbaImage) -> f32 {
    if a.dimensions() != b.dimensions() || a.is_empty() {
        return 100.0;
    }
    let rgb = |p: &image::Rgba<u8>| [p.0[0], p.0[1], p.0[2]];
    let seen = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| p != q && delta_e_2000(lab(rgb(p)), lab(rgb(q))) >= f64::from(VISIBLE_DELTA_E))
        .count();
    100.0 * seen as f32 / (a.width() * a.height()) as f32
}

/// The share of `picture`'s pixels, percent, that differ visibly from its most common colour:
/// a blank or one-colour side holds almost none.
pub fn picture_percent(picture: &RgbaImage) -> f32 {
    let mut counts = std::collections::HashMap::new();
    for p in picture.pixels() {
        *counts.entry(p.0).or_insert(0usize) += 1;
    }
    let Some((&common, _)) = counts.iter().max_by_key(|&(_, &n)| n) else { return 0.0 };
    let common_lab = lab([common[0], common[1], common[2]]);
    let seen = picture
        .pixels()
        .filter(|p| {
            p.0 != common && delta_e_2000(lab([p.0[0], p.0[1], p.0[2]]), common_lab) >= f64::from(VISIBLE_DELTA_E)
        })
        .count();
    100.0 * seen as f32 / (picture.width() * picture.height()) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sharma, Wu & Dalal's test data (Table 1): pairs 1, 7, 13, 17, 25 and 34 with their
    /// published ΔE₀₀ to four decimals.
    #[test]
    fn ciede2000_matches_the_published_test_pairs() {
        let pairs = [
            ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
            ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
            ([50.0, 2.49, -0.001], [50.0, -2.49, 0.0011], 7.2195),
            ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0], 27.1492),
            ([60.2574, -34.0099, 36.2677], [60.4626, -34.1751, 39.4387], 1.2644),
            ([6.7747, -0.2908, -2.4247], [5.8714, -0.0985, -2.2286], 0.6377),
        ];
        for (a, b, expected) in pairs {
            let got = delta_e_2000(a, b);
            assert!((got - expected).abs() < 5e-5, "{a:?} {b:?}: {got:.4}, published {expected}");
            assert!((delta_e_2000(b, a) - got).abs() < 1e-9, "symmetric");
        }
    }

    #[test]
    fn white_is_lab_100_and_a_one_colour_picture_holds_nothing() {
        let [l, a, b] = lab([255, 255, 255]);
        assert!((l - 100.0).abs() < 1e-3 && a.abs() < 1e-3 && b.abs() < 1e-3, "{l} {a} {b}");
        let grey = RgbaImage::from_pixel(8, 8, image::Rgba([90, 90, 90, 255]));
        assert_eq!(picture_percent(&grey), 0.0);
        let mut half = grey.clone();
        (0..4).for_each(|x| (0..8).for_each(|y| half.put_pixel(x, y, image::Rgba([200, 40, 40, 255]))));
        assert_eq!(visible_percent(&grey, &half), 50.0);
        assert!(picture_percent(&half) > 0.0);
    }
}
