//! `<texture type="bitmap">`: loads the image (PNG/JPEG through `image`, sRGB decoded to
//! linear unless `raw`; EXR linear) and reads `filter_type`, `wrap_mode` and `to_uv`.

use glam::{Affine2, Mat2, Vec2};

use super::XmlError;
use super::build::Context;
use super::props::Props;
use super::tree::Element;
use crate::image::io::{read_image, srgb_to_linear};
use crate::image::limits::open_image;
use crate::math::Spectrum;
use crate::scene::texture::{Texture, Wrap};

/// Largest texture side accepted.
const MAX_SIDE: u32 = 16384;

/// Builds a bitmap texture.
pub fn load_bitmap(el: &Element, ctx: &mut Context<'_>) -> Result<Texture, XmlError> {
    let ty = el.required("type")?;
    if ty != "bitmap" {
        return Err(el.error(format!("texture \"{ty}\" is not supported (known: bitmap)")));
    }
    let p = Props::new(el)?;
    let file = p.string("filename", "")?;
    if file.is_empty() {
        return Err(el.error("missing <string name=\"filename\">"));
    }
    let path = el.dir.join(&file);
    let raw = p.bool("raw", false)?;
    let bilinear = match p.string("filter_type", "bilinear")?.as_str() {
        "bilinear" => true,
        "nearest" => false,
        other => {
            return Err(p.error_at(
                "filter_type",
                format!("unknown filter_type \"{other}\" (known: bilinear, nearest)"),
            ));
        }
    };
    let wrap = match p.string("wrap_mode", "repeat")?.as_str() {
        "repeat" => Wrap::Repeat,
        "mirror" => Wrap::Mirror,
        "clamp" => Wrap::Clamp,
        other => {
            return Err(p.error_at(
                "wrap_mode",
                format!("unknown wrap_mode \"{other}\" (known: repeat, mirror, clamp)"),
            ));
        }
    };
    let m = p.transform("to_uv")?;
    let to_uv = Affine2::from_mat2_translation(
        Mat2::from_cols(
            m.x_axis.truncate().truncate(),
            m.y_axis.truncate().truncate(),
        ),
        Vec2::new(m.w_axis.x, m.w_axis.y),
    );
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let (width, height, texels) = match ext.as_str() {
        "exr" | "pfm" => {
            let img = read_image(&path).map_err(|e| p.error_at("filename", e))?;
            (img.width, img.height, img.rgb)
        }
        "png" | "jpg" | "jpeg" => {
            let img = open_image(&path)
                .map_err(|e| {
                    p.error_at(
                        "filename",
                        format!("cannot read texture \"{}\": {e}", path.display()),
                    )
                })?
                .to_rgb8();
            let decode = |v: u8| {
                let x = v as f32 / 255.0;
                if raw { x } else { srgb_to_linear(x) }
            };
            let texels = img
                .pixels()
                .map(|px| Spectrum::from_array(px.0.map(decode)))
                .collect();
            (img.width(), img.height(), texels)
        }
        other => {
            return Err(el.error(format!(
                "texture \"{}\": unknown image format \".{other}\" (known: .png, .jpg, .exr)",
                path.display()
            )));
        }
    };
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(el.error(format!("texture size {width}x{height} is out of range")));
    }
    if !texels.iter().all(|t| t.is_finite()) {
        return Err(el.error(format!(
            "texture \"{}\" has non-finite texels",
            path.display()
        )));
    }
    ctx.finish(&p)?;
    Ok(Texture {
        width,
        height,
        texels,
        bilinear,
        wrap,
        to_uv,
    })
}
