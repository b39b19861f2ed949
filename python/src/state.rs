//! A render's result as bytes, for pickling (Dask moves results between processes):
//! the film's Welford statistics per pixel, exactly, so passes rendered elsewhere merge
//! as they would in one process. Little-endian; starts with a magic word and a version.

use std::time::Duration;

use lightlab::image::{Film, PixelStats};
use lightlab::math::Spectrum;
use lightlab::render::RenderOutput;
use lightlab::settings::{Pass, SampleBlock};

const MAGIC: &[u8; 4] = b"LLR3";
/// Bytes per pixel: count, mean (3), M2 (3), weight, weight², 4 bytes each.
const PIXEL_BYTES: usize = 36;

/// A render's output with what the Python result shows beside it.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// Film, spp, time, invalid samples, stopped, shadow rays, sample blocks.
    pub out: RenderOutput,
    /// The canonical flags of the render.
    pub settings: String,
    /// The pass rendered.
    pub pass: Pass,
    /// The scene's name.
    pub scene: String,
}

fn put_str(b: &mut Vec<u8>, s: &str) {
    b.extend((s.len() as u32).to_le_bytes());
    b.extend(s.as_bytes());
}

/// `rendered` as bytes.
pub fn encode(r: &Rendered) -> Vec<u8> {
    let film = &r.out.film;
    let mut b = Vec::with_capacity(64 + film.pixels.len() * PIXEL_BYTES);
    b.extend(MAGIC);
    for v in [
        film.width,
        film.height,
        r.out.spp,
        r.pass.index,
        r.pass.count,
    ] {
        b.extend(v.to_le_bytes());
    }
    b.extend(r.out.invalid_samples.to_le_bytes());
    b.extend(r.out.shadow_rays.to_le_bytes());
    b.extend(r.out.time.as_secs_f64().to_le_bytes());
    b.push(r.out.stopped as u8);
    put_str(&mut b, &r.settings);
    put_str(&mut b, &r.scene);
    b.extend((r.out.samples.len() as u32).to_le_bytes());
    for block in &r.out.samples {
        b.extend(block.seed.to_le_bytes());
        b.extend(block.first.to_le_bytes());
        b.extend(block.last.to_le_bytes());
    }
    for p in &film.pixels {
        b.extend(p.count.to_le_bytes());
        for v in p.mean.to_array().into_iter().chain(p.m2.to_array()) {
            b.extend(v.to_le_bytes());
        }
        b.extend(p.weight.to_le_bytes());
        b.extend(p.weight2.to_le_bytes());
    }
    b
}

/// Reads bytes in order; every read checks the length.
struct Reader<'a>(&'a [u8]);

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], String> {
        if self.0.len() < N {
            return Err("result state is truncated".into());
        }
        let (head, rest) = self.0.split_at(N);
        self.0 = rest;
        head.try_into()
            .map_err(|_| "result state is truncated".to_string())
    }
    fn u32(&mut self) -> Result<u32, String> {
        self.take::<4>().map(u32::from_le_bytes)
    }
    fn f32(&mut self) -> Result<f32, String> {
        self.take::<4>().map(f32::from_le_bytes)
    }
    fn spectrum(&mut self) -> Result<Spectrum, String> {
        Ok(Spectrum::new(self.f32()?, self.f32()?, self.f32()?))
    }
    fn string(&mut self) -> Result<String, String> {
        let n = self.u32()? as usize;
        if self.0.len() < n {
            return Err("result state is truncated".into());
        }
        let (head, rest) = self.0.split_at(n);
        self.0 = rest;
        String::from_utf8(head.to_vec()).map_err(|e| e.to_string())
    }
}

/// The result `bytes` describe (written by [`encode`]).
pub fn decode(bytes: &[u8]) -> Result<Rendered, String> {
    let mut r = Reader(bytes);
    if &r.take::<4>()? != MAGIC {
        return Err("not a lightlab result state".into());
    }
    let (width, height, spp) = (r.u32()?, r.u32()?, r.u32()?);
    let pass = Pass {
        index: r.u32()?,
        count: r.u32()?,
    };
    let invalid_samples = u64::from_le_bytes(r.take::<8>()?);
    let shadow_rays = u64::from_le_bytes(r.take::<8>()?);
    let time = f64::from_le_bytes(r.take::<8>()?);
    let stopped = r.take::<1>()?[0] != 0;
    let (settings, scene) = (r.string()?, r.string()?);
    let blocks = r.u32()? as usize;
    // 16 bytes per block: a count larger than the rest of the state is truncation.
    if blocks > r.0.len() / 16 {
        return Err("result state is truncated".into());
    }
    let mut samples = Vec::with_capacity(blocks);
    for _ in 0..blocks {
        samples.push(SampleBlock {
            seed: u64::from_le_bytes(r.take::<8>()?),
            first: r.u32()?,
            last: r.u32()?,
        });
    }
    let n = width as usize * height as usize;
    if r.0.len() != n * PIXEL_BYTES {
        return Err(format!(
            "result state holds {} bytes of pixels, not {}",
            r.0.len(),
            n * PIXEL_BYTES
        ));
    }
    let mut pixels = Vec::with_capacity(n);
    for _ in 0..n {
        pixels.push(PixelStats {
            count: r.u32()?,
            mean: r.spectrum()?,
            m2: r.spectrum()?,
            weight: r.f32()?,
            weight2: r.f32()?,
        });
    }
    let out = RenderOutput {
        film: Film {
            width,
            height,
            pixels,
        },
        time: Duration::try_from_secs_f64(time).unwrap_or_default(),
        spp,
        invalid_samples,
        stopped,
        shadow_rays,
        samples,
    };
    Ok(Rendered {
        out,
        settings,
        pass,
        scene,
    })
}
