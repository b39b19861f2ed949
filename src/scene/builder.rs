//! Building scenes in code: add shapes with materials and emission, then `build`.

use std::sync::Arc;

use glam::Vec3;

use super::texture::{MaterialTexture, Texture};
use super::{Scene, SceneError};
use crate::bsdf::Material;
use crate::geometry::shape::{Disk, Rectangle, Sphere, Triangle};
use crate::geometry::{Geometry, Mesh, NO_LIGHT, Primitive, Shape};
use crate::image::Filter;
use crate::light::{AreaLight, EmissionTexture, Environment, Light, PointLight, PolygonLight};
use crate::math::Spectrum;
use crate::scene::Camera;
use crate::settings::RenderPatch;

/// Emission of a shape: radiance, an optional radiance texture, and sidedness.
#[derive(Clone, Debug)]
pub struct Emission {
    /// Radiance (a factor on the texture's value when there is one).
    pub radiance: Spectrum,
    /// A radiance texture over the shape's texture coordinates (rectangles, disks and
    /// spheres only).
    pub texture: Option<Arc<Texture>>,
    /// Emits from both sides.
    pub two_sided: bool,
}

impl Emission {
    /// One-sided emission of radiance `r`.
    pub fn new(r: Spectrum) -> Emission {
        Emission {
            radiance: r,
            texture: None,
            two_sided: false,
        }
    }

    /// One-sided emission of the radiance texture `t`.
    pub fn textured(t: Texture) -> Emission {
        Emission {
            radiance: Spectrum::ONE,
            texture: Some(Arc::new(t)),
            two_sided: false,
        }
    }
}

/// Collects shapes, materials and lights into a [`Scene`].
#[derive(Debug)]
pub struct SceneBuilder {
    name: String,
    prims: Vec<Primitive>,
    meshes: Vec<Mesh>,
    materials: Vec<Material>,
    lights: Vec<Light>,
    two_sided: Vec<bool>,
    textures: Vec<Option<MaterialTexture>>,
    /// Problems found while adding shapes, reported by `build`.
    errors: Vec<String>,
}

impl SceneBuilder {
    /// An empty scene called `name`.
    pub fn new(name: impl Into<String>) -> SceneBuilder {
        SceneBuilder {
            name: name.into(),
            prims: Vec::new(),
            meshes: Vec::new(),
            materials: Vec::new(),
            lights: Vec::new(),
            two_sided: Vec::new(),
            textures: Vec::new(),
            errors: Vec::new(),
        }
    }

    /// Adds a material and returns its index.
    pub fn material(&mut self, m: Material) -> u32 {
        self.materials.push(m);
        self.materials.len() as u32 - 1
    }

    /// Marks material `m` as reflecting from both sides (Mitsuba's `twosided`: a hit
    /// seen from behind is shaded with the normal flipped).
    pub fn set_two_sided(&mut self, m: u32) -> &mut Self {
        if self.two_sided.len() <= m as usize {
            self.two_sided.resize(m as usize + 1, false);
        }
        self.two_sided[m as usize] = true;
        self
    }

    /// Textures material `m`'s reflectance.
    pub fn set_texture(&mut self, m: u32, texture: MaterialTexture) -> &mut Self {
        if self.textures.len() <= m as usize {
            self.textures.resize(m as usize + 1, None);
        }
        self.textures[m as usize] = Some(texture);
        self
    }

    /// Adds a shape; if it emits, it also becomes a light.
    pub fn shape(&mut self, shape: Shape, material: u32, emission: Option<Emission>) -> &mut Self {
        let light = match emission {
            Some(e) => {
                let texture = match e.texture {
                    Some(t) => match EmissionTexture::new(t, &shape) {
                        Ok(t) => Some(Arc::new(t)),
                        Err(e) => {
                            self.errors.push(format!(
                                "a radiance texture cannot emit from a {} (only rectangles, \
                                 disks and spheres have texture coordinates of their own)",
                                e.0
                            ));
                            None
                        }
                    },
                    None => None,
                };
                self.lights.push(Light::Area(AreaLight {
                    shape,
                    radiance: e.radiance,
                    two_sided: e.two_sided,
                    texture,
                }));
                self.lights.len() as u32 - 1
            }
            None => NO_LIGHT,
        };
        self.prims.push(Primitive {
            shape,
            material,
            light,
        });
        self
    }

    /// Adds a sphere.
    pub fn sphere(
        &mut self,
        center: Vec3,
        radius: f32,
        material: u32,
        emission: Option<Emission>,
    ) -> &mut Self {
        self.shape(
            Shape::Sphere(Sphere::new(center, radius)),
            material,
            emission,
        )
    }

    /// Adds a rectangle with corner `o` and perpendicular edges `ea`, `eb` (front side
    /// ea × eb). Non-perpendicular or degenerate edges are a programming error in a
    /// built-in scene and are reported when the scene is built.
    pub fn rectangle(
        &mut self,
        o: Vec3,
        ea: Vec3,
        eb: Vec3,
        material: u32,
        emission: Option<Emission>,
    ) -> &mut Self {
        match Rectangle::new(o, ea, eb) {
            Some(r) => self.shape(Shape::Rectangle(r), material, emission),
            None => {
                // Keep a degenerate marker so `build` can report it.
                self.prims.push(Primitive {
                    shape: Shape::Disk(Disk {
                        center: o,
                        normal: Vec3::ZERO,
                        radius: f32::NAN,
                        axes: [Vec3::ZERO; 2],
                    }),
                    material,
                    light: NO_LIGHT,
                });
                self
            }
        }
    }

    /// Adds a disk.
    pub fn disk(
        &mut self,
        center: Vec3,
        normal: Vec3,
        radius: f32,
        material: u32,
        emission: Option<Emission>,
    ) -> &mut Self {
        self.shape(
            Shape::Disk(Disk::new(center, normal.normalize(), radius)),
            material,
            emission,
        )
    }

    /// Adds a triangle mesh; with emission, every triangle becomes a light.
    pub fn mesh(&mut self, mesh: Mesh, material: u32, emission: Option<Emission>) -> &mut Self {
        let mesh_index = self.meshes.len() as u32;
        for (i, &[a, b, c]) in mesh.indices.iter().enumerate() {
            let (p0, p1, p2) = (
                mesh.positions[a as usize],
                mesh.positions[b as usize],
                mesh.positions[c as usize],
            );
            let tri = Triangle {
                p0,
                e1: p1 - p0,
                e2: p2 - p0,
                mesh: mesh_index,
                index: i as u32,
            };
            self.shape(Shape::Triangle(tri), material, emission.clone());
        }
        self.meshes.push(mesh);
        self
    }

    /// Adds a planar polygon (convex or concave, vertices in order; front side
    /// right-handed with that order) as the mesh of its ear-clipped triangulation. With
    /// emission it becomes one [`PolygonLight`] that all its triangles point to. An
    /// invalid outline is reported when the scene is built.
    pub fn polygon(
        &mut self,
        vertices: &[Vec3],
        material: u32,
        emission: Option<Emission>,
    ) -> &mut Self {
        let light = match PolygonLight::new(vertices, Spectrum::ZERO) {
            Ok(l) => l,
            Err(e) => {
                self.errors.push(format!("polygon {vertices:?}: {e}"));
                return self;
            }
        };
        let n = light.polygon.normal();
        // Each triangle wound like the polygon, so its normal is the emitting side.
        let indices = light
            .polygon
            .triangles()
            .iter()
            .map(|&[a, b, c]| {
                let (pa, pb, pc) = (vertices[a], vertices[b], vertices[c]);
                if (pb - pa).cross(pc - pa).dot(n) >= 0.0 {
                    [a as u32, b as u32, c as u32]
                } else {
                    [a as u32, c as u32, b as u32]
                }
            })
            .collect();
        let mesh = Mesh {
            positions: vertices.to_vec(),
            indices,
            ..Mesh::default()
        };
        let light_index = match emission {
            Some(e) if e.texture.is_some() => {
                self.errors
                    .push("a radiance texture cannot emit from a polygon".to_owned());
                NO_LIGHT
            }
            Some(e) => {
                self.lights.push(Light::Polygon(PolygonLight {
                    radiance: e.radiance,
                    two_sided: e.two_sided,
                    ..light
                }));
                self.lights.len() as u32 - 1
            }
            None => NO_LIGHT,
        };
        let first = self.prims.len();
        self.mesh(mesh, material, None);
        for p in &mut self.prims[first..] {
            p.light = light_index;
        }
        self
    }

    /// Adds a point light.
    pub fn point_light(&mut self, position: Vec3, intensity: Spectrum) -> &mut Self {
        self.lights.push(Light::Point(PointLight {
            position,
            intensity,
        }));
        self
    }

    /// Adds an environment (at most one per scene).
    pub fn environment(&mut self, env: Environment) -> &mut Self {
        self.lights.push(Light::Environment(env));
        self
    }

    /// Validates and builds the scene (this builds the BVH).
    pub fn build(self, camera: Camera, spp: u32) -> Result<Scene, SceneError> {
        let err = |m: String| SceneError::new(self.name.clone(), None, m);
        if let Some(e) = self.errors.first() {
            return Err(err(e.clone()));
        }
        for (i, p) in self.prims.iter().enumerate() {
            let b = p.shape.bounds();
            if !(b.min.is_finite() && b.max.is_finite()) || p.shape.area().is_nan() {
                return Err(err(format!(
                    "shape {i} is degenerate or not finite: {:?}",
                    p.shape
                )));
            }
            if p.material as usize >= self.materials.len() {
                return Err(err(format!(
                    "shape {i} uses material {} of {}",
                    p.material,
                    self.materials.len()
                )));
            }
        }
        let geometry = Geometry::new(self.prims, self.meshes);
        let mut lights = self.lights;
        let mut environments = lights.iter().enumerate().filter(|(_, l)| l.is_infinite());
        let environment = environments.next().map(|(i, _)| i);
        if environments.next().is_some() {
            return Err(err(
                "a scene can have at most one environment emitter".into()
            ));
        }
        if let Some(i) = environment
            && let Light::Environment(e) = &mut lights[i]
        {
            // Φ = π r² ∫L dω needs the radius of a sphere around the scene.
            let b = geometry.bounds();
            let r = 0.5 * (b.max - b.min).length();
            e.scene_radius = if r.is_finite() && r > 0.0 { r } else { 1.0 };
        }
        Ok(Scene {
            name: self.name,
            camera,
            geometry,
            materials: self.materials,
            lights,
            environment,
            spp,
            two_sided: self.two_sided,
            filter: Filter::default(),
            requested: RenderPatch::default(),
            textures: self.textures,
            content_hash: 0,
        })
    }
}
