//! The scattering math of the path tracer: directions around a normal,
//! GGX microfacet sampling and Smith masking, Schlick and exact dielectric
//! Fresnel, reflection and refraction. All through libm, so every target
//! computes the same bits.

use core::f32::consts::TAU;

use glam::{Vec2, Vec3};

use crate::math::sqrt32;

/// `local` (around `+z`) turned to the frame around the unit vector `n`
/// (Duff et al. 2017, a branchless orthonormal basis).
#[inline]
#[must_use]
pub(crate) fn around_normal(n: Vec3, local: Vec3) -> Vec3 {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let s = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    t * local.x + s * local.y + n * local.z
}

/// A direction uniform over the cone of half-angle `acos(cos_max)` around
/// the unit vector `axis`.
#[must_use]
pub(crate) fn cone(axis: Vec3, cos_max: f32, u: Vec2) -> Vec3 {
    let cos = 1.0 - u.x * (1.0 - cos_max);
    let sin = sqrt32((1.0 - cos * cos).max(0.0));
    let phi = TAU * u.y;
    around_normal(
        axis,
        Vec3::new(sin * libm::cosf(phi), sin * libm::sinf(phi), cos),
    )
}

/// GGX's `alpha` for a perceptual roughness in `[0, 1]` (`roughness^2`),
/// kept above a floor at which the lobe is a mirror in all but name.
#[inline]
#[must_use]
pub(crate) fn alpha(roughness: f32) -> f32 {
    (roughness * roughness).max(1e-4)
}

/// A microfacet normal around the unit normal `n` drawn from GGX's
/// distribution of normals weighted by `n . m` (Walter et al. 2007), or
/// `n` itself for a perfect mirror (`roughness` 0).
#[must_use]
pub(crate) fn microfacet(n: Vec3, roughness: f32, u: Vec2) -> Vec3 {
    if roughness <= 0.0 {
        return n;
    }
    let a = alpha(roughness);
    // tan^2 theta = a^2 u / (1 - u), as cos^2 theta.
    let cos2 = (1.0 - u.x) / (1.0 + (a * a - 1.0) * u.x);
    let cos = sqrt32(cos2.clamp(0.0, 1.0));
    let sin = sqrt32((1.0 - cos * cos).max(0.0));
    let phi = TAU * u.y;
    around_normal(
        n,
        Vec3::new(sin * libm::cosf(phi), sin * libm::sinf(phi), cos),
    )
}

/// Smith's masking term for GGX at a direction with `cos = n . w > 0`.
#[inline]
#[must_use]
pub(crate) fn smith_g1(cos: f32, roughness: f32) -> f32 {
    if roughness <= 0.0 {
        return 1.0;
    }
    let a2 = alpha(roughness) * alpha(roughness);
    2.0 * cos / (cos + sqrt32(a2 + (1.0 - a2) * cos * cos))
}

/// The mirror image of the incident direction `d` about `m`.
#[inline]
#[must_use]
pub(crate) fn reflect(d: Vec3, m: Vec3) -> Vec3 {
    d - m * (2.0 * d.dot(m))
}

/// Schlick's Fresnel reflectance for normal-incidence reflectance `f0` at
/// `cos` between the view and the microfacet normal.
#[inline]
#[must_use]
pub(crate) fn schlick(f0: Vec3, cos: f32) -> Vec3 {
    let x = 1.0 - cos.clamp(0.0, 1.0);
    let c = x * x * x * x * x;
    f0 + (Vec3::ONE - f0) * c
}

/// A glossy reflection of the incident unit direction `d` off a surface of
/// unit normal `n` (facing `-d`) with microfacet normal `m`: the outgoing
/// direction and the weight `F G (v.m) / ((n.v)(n.m))` of sampling `m` by
/// [`microfacet`], `None` when the reflection goes below the surface.
#[must_use]
pub(crate) fn glossy(d: Vec3, n: Vec3, m: Vec3, f0: Vec3, roughness: f32) -> Option<(Vec3, Vec3)> {
    let v = -d;
    let out = reflect(d, m);
    let (nv, nl, nm, vm) = (n.dot(v), n.dot(out), n.dot(m), v.dot(m));
    if nl <= 0.0 || nv <= 0.0 || nm <= 0.0 || vm <= 0.0 {
        return None;
    }
    let g = smith_g1(nv, roughness) * smith_g1(nl, roughness);
    let weight = schlick(f0, vm) * (g * vm / (nv * nm));
    Some((out, weight))
}

/// The exact Fresnel reflectance of unpolarized light meeting a dielectric
/// interface at `cos_i` (from the side the light comes from) where `eta` is
/// the index behind the interface over the index in front; 1 for total
/// internal reflection.
#[must_use]
pub(crate) fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = sqrt32(1.0 - sin2_t);
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// The incident unit direction `d` refracted at normal `m` (facing `-d`),
/// `eta` being the index behind over the index in front; `None` for total
/// internal reflection.
#[must_use]
pub(crate) fn refract(d: Vec3, m: Vec3, eta: f32) -> Option<Vec3> {
    let ratio = 1.0 / eta;
    let cos_i = -d.dot(m);
    let sin2_t = ratio * ratio * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = sqrt32(1.0 - sin2_t);
    Some(d * ratio + m * (ratio * cos_i - cos_t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::sampling::r2;

    #[test]
    fn frames_are_orthonormal_and_keep_z_on_the_normal() {
        for i in 0..200 {
            let u = r2(i, 99);
            let n = cone(Vec3::new(0.3, -0.8, 0.5).normalize(), -1.0, u);
            let d = around_normal(n, Vec3::Z);
            assert!((d - n).length() < 1e-5);
            let x = around_normal(n, Vec3::X);
            assert!(x.dot(n).abs() < 1e-5 && (x.length() - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn fresnel_matches_known_values() {
        // Normal incidence on n = 1.5: ((1.5 - 1) / (1.5 + 1))^2 = 0.04.
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-6);
        // Grazing: everything reflects.
        assert!((fresnel_dielectric(0.0, 1.5) - 1.0).abs() < 1e-6);
        // Inside glass beyond the critical angle (asin(1/1.5) = 41.8 deg).
        assert_eq!(fresnel_dielectric(libm::cosf(0.8), 1.0 / 1.5), 1.0);
    }

    #[test]
    fn refraction_obeys_snell() {
        let n = Vec3::Y;
        for i in 1..50 {
            let theta = i as f32 * 0.03;
            let d = Vec3::new(libm::sinf(theta), -libm::cosf(theta), 0.0);
            let t = refract(d, n, 1.33).unwrap();
            assert!((t.length() - 1.0).abs() < 1e-5);
            let sin_t = t.x;
            assert!((libm::sinf(theta) - 1.33 * sin_t).abs() < 1e-5);
            assert!(t.y < 0.0);
        }
    }

    #[test]
    fn a_mirror_reflects_exactly_and_keeps_the_colors_energy_at_normal_incidence() {
        let d = Vec3::new(0.6, -0.8, 0.0);
        let (out, w) = glossy(d, Vec3::Y, Vec3::Y, Vec3::splat(0.5), 0.0).unwrap();
        assert!((out - Vec3::new(0.6, 0.8, 0.0)).length() < 1e-6);
        // Schlick at cos 0.8: 0.5 + 0.5 * 0.2^5.
        assert!((w.x - (0.5 + 0.5 * 0.2f32.powi(5))).abs() < 1e-6);
    }

    #[test]
    fn glossy_weights_stay_at_most_one_for_white_metal() {
        // The weight F G (v.m) / ((n.v)(n.m)) is an energy ratio: with F = 1
        // it never exceeds 1 by more than float error (Smith G <= 1 keeps
        // the lobe from creating energy).
        let d = Vec3::new(0.5, -0.7, 0.2).normalize();
        let mut sum = 0.0;
        let n = 4096;
        for i in 0..n {
            let m = microfacet(Vec3::Y, 0.5, r2(i, 7));
            if let Some((_, w)) = glossy(d, Vec3::Y, m, Vec3::ONE, 0.5) {
                sum += w.x;
            }
        }
        let mean = sum / n as f32;
        assert!(mean <= 1.0 && mean > 0.8, "{mean}");
    }
}
