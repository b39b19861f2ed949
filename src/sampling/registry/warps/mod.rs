//! Registry rows for the warps, with the parameters each is tested at (Phong exponents,
//! cone angles, spherical shapes seen from near, far and grazing points): the square,
//! disk, hemisphere, sphere, lobe, 1-D and planar warps here, the spherical triangles,
//! rectangles and polygons in [`spherical`].

mod spherical;

use glam::{Vec2, Vec3};

use super::{Draw, Entry, Family, boxed};
use crate::sampling::Rng32;
use crate::sampling::chi2::Domain;
use crate::sampling::warp::*;

fn entry(
    name: &str,
    description: &str,
    domain: Domain,
    draw: Draw,
    pdf: Box<dyn Fn(Vec3) -> f32 + Send + Sync>,
) -> Entry {
    Entry {
        name: name.into(),
        description: description.into(),
        family: Family::Warp,
        domain,
        draw,
        pdf,
        inverse: None,
        samples: 1_000_000,
        resolution: None,
    }
}

fn with_inverse(mut e: Entry, inverse: Box<dyn Fn(Vec3) -> Vec2 + Send + Sync>) -> Entry {
    e.inverse = Some(inverse);
    e
}

fn square(f: impl Fn(Vec2) -> (Vec3, f32) + Send + Sync + 'static) -> Draw {
    Draw::Square(boxed(f))
}

fn stream(f: impl Fn(&mut Rng32) -> (Vec3, f32) + Send + Sync + 'static) -> Draw {
    Draw::Stream(Box::new(f))
}

fn flat(p: Vec2) -> Vec3 {
    p.extend(0.0)
}

fn basic_entries() -> Vec<Entry> {
    vec![
        with_inverse(
            entry(
                "sphere-uniform",
                "uniform sphere by (z, phi)",
                Domain::sphere(),
                square(square_to_uniform_sphere),
                boxed(uniform_sphere_pdf),
            ),
            boxed(uniform_sphere_to_square),
        ),
        entry(
            "sphere-cube-rejection",
            "uniform sphere by rejection from the cube",
            Domain::sphere(),
            stream(cube_rejection_to_sphere),
            boxed(uniform_sphere_pdf),
        ),
        with_inverse(
            entry(
                "hemisphere-uniform",
                "uniform hemisphere by (z, phi)",
                Domain::hemisphere(),
                square(square_to_uniform_hemisphere),
                boxed(uniform_hemisphere_pdf),
            ),
            boxed(uniform_hemisphere_to_square),
        ),
        entry(
            "hemisphere-cube-rejection",
            "uniform hemisphere by rejection from the cube",
            Domain::hemisphere(),
            stream(cube_rejection_to_hemisphere),
            boxed(uniform_hemisphere_pdf),
        ),
        with_inverse(
            entry(
                "hemisphere-theta-phi",
                "uniform (theta, phi): crowds the pole, true pdf 1/(pi^2 sin theta)",
                Domain::hemisphere(),
                square(square_to_theta_phi_hemisphere),
                boxed(theta_phi_hemisphere_pdf),
            ),
            boxed(theta_phi_hemisphere_to_square),
        ),
        with_inverse(
            entry(
                "cosine-concentric",
                "cosine hemisphere by Malley over the concentric disk",
                Domain::hemisphere(),
                square(square_to_cosine_hemisphere),
                boxed(cosine_hemisphere_pdf),
            ),
            boxed(cosine_hemisphere_to_square),
        ),
        entry(
            "cosine-malley-rejection",
            "cosine hemisphere by Malley over the rejection disk",
            Domain::hemisphere(),
            stream(malley_rejection_hemisphere),
            boxed(cosine_hemisphere_pdf),
        ),
        with_inverse(
            entry(
                "disk-polar",
                "uniform disk by r = sqrt(u0), phi = 2 pi u1",
                Domain::square(-1.0, 1.0),
                square(|u| {
                    (
                        flat(square_to_uniform_disk_polar(u)),
                        uniform_disk_pdf(square_to_uniform_disk_polar(u)),
                    )
                }),
                boxed(|x: Vec3| uniform_disk_pdf(x.truncate())),
            ),
            boxed(|x: Vec3| uniform_disk_polar_to_square(x.truncate())),
        ),
        with_inverse(
            entry(
                "disk-concentric",
                "uniform disk by Shirley-Chiu concentric map",
                Domain::square(-1.0, 1.0),
                square(|u| {
                    let p = square_to_uniform_disk_concentric(u);
                    (flat(p), uniform_disk_pdf(p))
                }),
                boxed(|x: Vec3| uniform_disk_pdf(x.truncate())),
            ),
            boxed(|x: Vec3| uniform_disk_concentric_to_square(x.truncate())),
        ),
        entry(
            "disk-rejection",
            "uniform disk by rejection from the square",
            Domain::square(-1.0, 1.0),
            stream(|r| {
                let p = disk_rejection(r);
                (flat(p), uniform_disk_pdf(p))
            }),
            boxed(|x: Vec3| uniform_disk_pdf(x.truncate())),
        ),
        with_inverse(
            entry(
                "xi-squared",
                "the lecture's x = u^2, pdf 1/(2 sqrt x)",
                Domain::UNIT_INTERVAL,
                square(|u| {
                    let (x, p) = uniform_to_xi_squared(u.x);
                    (Vec3::new(x, 0.0, 0.0), p)
                }),
                boxed(|x: Vec3| xi_squared_pdf(x.x)),
            ),
            boxed(|x: Vec3| Vec2::new(xi_squared_to_uniform(x.x), 0.0)),
        ),
        with_inverse(
            entry(
                "bilinear",
                "density ∝ bilinear weights 0.05, 1, 2, 0.5 at the corners (Hart et al. 2020)",
                Domain::UNIT_SQUARE,
                square(|u| {
                    let (p, pdf) = square_to_bilinear(u, BILINEAR_TEST_WEIGHTS);
                    (flat(p), pdf)
                }),
                boxed(|x: Vec3| bilinear_pdf(x.truncate(), BILINEAR_TEST_WEIGHTS)),
            ),
            boxed(|x: Vec3| bilinear_to_square(x.truncate(), BILINEAR_TEST_WEIGHTS)),
        ),
    ]
}

/// Corner weights of the registry's bilinear row: uneven, one nearly zero.
const BILINEAR_TEST_WEIGHTS: [f32; 4] = [0.05, 1.0, 2.0, 0.5];

fn lobe_entries() -> Vec<Entry> {
    let mut list = Vec::new();
    list.extend([1.0f32, 10.0, 100.0, 1000.0].map(phong_entry));
    list.extend([1.0f32, 30.0, 90.0, 150.0].map(cone_entry));
    list
}

/// The Phong lobe cosⁿ θ (`phong-N`, any exponent n ≥ 0: `lightlab warp phong-37`).
pub(super) fn phong_entry(n: f32) -> Entry {
    // A cap holding all but 10⁻⁴ of the lobe: P(cos θ < z) = z^(n+1).
    let z_min = if n < 50.0 {
        0.0
    } else {
        1e-4f32.powf(1.0 / (n + 1.0))
    };
    let e = entry(
        &format!("phong-{n}"),
        &format!("Phong lobe cos^{n}: theta = arccos u0^(1/(n+1))"),
        Domain::cap(Vec3::Z, z_min),
        square(move |u| square_to_phong_lobe(u, n)),
        boxed(move |w| phong_lobe_pdf(w, n)),
    );
    with_inverse(e, boxed(move |w| phong_lobe_to_square(w, n)))
}

/// The uniform cone of half-angle `degrees` (`cone-D`, 0 < D ≤ 180: `lightlab warp
/// cone-12`).
pub(super) fn cone_entry(degrees: f32) -> Entry {
    let cos_max = degrees.to_radians().cos();
    let e = entry(
        &format!("cone-{degrees}"),
        &format!("uniform cone of half-angle {degrees} degrees"),
        Domain::cap(Vec3::Z, cos_max),
        square(move |u| square_to_uniform_cone(u, cos_max)),
        boxed(move |w| uniform_cone_pdf(w, cos_max)),
    );
    with_inverse(e, boxed(move |w| uniform_cone_to_square(w, cos_max)))
}

fn planar_entries() -> Vec<Entry> {
    let (p0, p1, p2) = (
        Vec3::new(0.5, -0.2, 0.1),
        Vec3::new(2.0, 0.3, 0.6),
        Vec3::new(0.2, 1.4, -0.3),
    );
    let triangle = Domain::Plane {
        origin: p0,
        edge_u: p1 - p0,
        edge_v: p2 - p0,
    };
    let on_triangle = move |b: Vec2| sample_triangle(p0, p1, p2, b).unwrap_or((p0, 0.0));
    let pdf = move || boxed(move |x: Vec3| triangle_pdf(p0, p1, p2, x));
    let mut list = vec![
        entry(
            "triangle-rejection",
            "uniform triangle: barycentrics by rejection (a + b < 1)",
            triangle,
            stream(move |r| on_triangle(triangle_rejection(r))),
            pdf(),
        ),
        entry(
            "triangle-fold",
            "uniform triangle: fold (a, b) -> (1 - a, 1 - b) above the diagonal",
            triangle,
            square(move |u| on_triangle(square_to_triangle_fold(u))),
            pdf(),
        ),
        with_inverse(
            entry(
                "triangle-sqrt",
                "uniform triangle: square-root map (b1, b2) = sqrt(u0)(1 - u1, u1)",
                triangle,
                square(move |u| on_triangle(square_to_triangle_sqrt(u))),
                pdf(),
            ),
            boxed(move |x| triangle_sqrt_to_square(triangle_to_barycentrics(p0, p1, p2, x))),
        ),
    ];
    let (a, b, d) = (
        Vec3::new(-1.0, 0.0, 0.5),
        Vec3::new(1.0, 0.5, 0.0),
        Vec3::new(-0.5, 1.0, 1.5),
    );
    list.push(with_inverse(
        entry(
            "parallelogram",
            "uniform parallelogram a + u0 (b - a) + u1 (d - a)",
            Domain::Plane {
                origin: a,
                edge_u: b - a,
                edge_v: d - a,
            },
            square(move |u| square_to_parallelogram(a, b, d, u).unwrap_or((a, 0.0))),
            boxed(move |x| parallelogram_pdf(a, b, d, x)),
        ),
        boxed(move |x| parallelogram_to_square(a, b, d, x)),
    ));
    // Polygons in a tilted plane: an L (concave) and an octagon (convex).
    let (origin, eu, ev) = (
        Vec3::new(0.2, 0.1, -0.3),
        Vec3::new(1.0, 0.2, 0.3),
        Vec3::new(-0.1, 0.8, 0.4),
    );
    let l_shape = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)];
    let octagon = [
        (1., 0.),
        (2., 0.),
        (3., 1.),
        (3., 2.),
        (2., 3.),
        (1., 3.),
        (0., 2.),
        (0., 1.),
    ];
    for (shape, outline, size) in [("l", &l_shape[..], 2.0), ("octagon", &octagon[..], 3.0)] {
        let vertices: Vec<Vec3> = outline
            .iter()
            .map(|&(s, t)| origin + s * eu + t * ev)
            .collect();
        let Ok(polygon) = Polygon::new(&vertices) else {
            continue;
        };
        let domain = Domain::Plane {
            origin,
            edge_u: eu * size,
            edge_v: ev * size,
        };
        let (p1, p2, p3, p4) = (polygon.clone(), polygon.clone(), polygon.clone(), polygon);
        list.push(entry(
            &format!("polygon-{shape}-rejection"),
            "uniform planar polygon by rejection from its bounding rectangle",
            domain,
            stream(move |r| p1.sample_rejection(r)),
            boxed(move |x| p2.pdf(x)),
        ));
        list.push(entry(
            &format!("polygon-{shape}-triangulated"),
            "uniform planar polygon by area-weighted ear-clipped triangles",
            domain,
            square(move |u| p3.sample_triangulated(u)),
            boxed(move |x| p4.pdf(x)),
        ));
    }
    list
}

pub(super) fn entries() -> Vec<Entry> {
    let mut list = basic_entries();
    list.extend(spherical::projected_entries());
    list.extend(lobe_entries());
    list.extend(planar_entries());
    list.extend(spherical::spherical_entries());
    list
}
