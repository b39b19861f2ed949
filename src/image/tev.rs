//! A live view in the tev image viewer (Müller, github.com/Tom94/tev) over its IPC
//! protocol, as pbrt-v4's `--display-server` uses it: one `CreateImage` packet names the
//! image and its channels, then an `UpdateImageV3` packet carries the pixels after every
//! round. Every packet is little-endian and starts with its total length (u32, counting
//! the length itself) and a type byte; strings end with a NUL byte.
//!
//! [`TevDisplay`] sends from a background thread and drops a frame when the previous one
//! is still on its way, so a slow viewer never slows the render; a viewer that cannot be
//! reached costs one warning.

use std::io::Write;
use std::net::TcpStream;
use std::sync::mpsc::{SyncSender, TrySendError, sync_channel};
use std::thread::JoinHandle;
use std::time::Duration;

use super::Film;
use crate::math::Spectrum;

/// tev's packet type `CreateImage` (tev `src/Ipc.cpp`, `IpcPacket::Type`).
pub const CREATE_IMAGE: u8 = 4;
/// tev's packet type `UpdateImageV3` (channel offsets and strides into one float array).
pub const UPDATE_IMAGE_V3: u8 = 6;
/// The channels lightlab sends.
pub const CHANNELS: [&str; 3] = ["R", "G", "B"];

/// A packet under construction: the length prefix is filled in by [`Packet::finish`].
struct Packet(Vec<u8>);

impl Packet {
    fn new(kind: u8, grab_focus: bool, name: &str) -> Packet {
        let mut p = Packet(vec![0; 4]);
        p.0.push(kind);
        p.0.push(grab_focus as u8);
        p.string(name);
        p
    }

    fn string(&mut self, s: &str) {
        // tev reads strings up to a NUL, so a NUL inside a name would cut it short.
        self.0.extend(s.bytes().filter(|&b| b != 0));
        self.0.push(0);
    }

    fn i32(&mut self, v: i32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    fn i64(&mut self, v: i64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }

    fn finish(mut self) -> Vec<u8> {
        let n = self.0.len() as u32;
        self.0[..4].copy_from_slice(&n.to_le_bytes());
        self.0
    }
}

/// `CreateImage`: an RGB image `name` of `width` × `height` pixels.
pub fn create_image_packet(name: &str, width: u32, height: u32) -> Vec<u8> {
    let mut p = Packet::new(CREATE_IMAGE, true, name);
    p.i32(width as i32);
    p.i32(height as i32);
    p.i32(CHANNELS.len() as i32);
    for c in CHANNELS {
        p.string(c);
    }
    p.finish()
}

/// `UpdateImageV3`: the whole of `film`'s means.
pub fn film_packet(name: &str, film: &Film) -> Vec<u8> {
    update_image_packet(
        name,
        film.width,
        film.height,
        film.pixels.iter().map(|p| p.mean),
    )
}

/// `UpdateImageV3`: a `width` × `height` image, row by row, as interleaved RGB (channel c
/// at offset c, stride 3).
pub fn update_image_packet(
    name: &str,
    width: u32,
    height: u32,
    rgb: impl ExactSizeIterator<Item = Spectrum>,
) -> Vec<u8> {
    let mut p = Packet::new(UPDATE_IMAGE_V3, false, name);
    p.i32(CHANNELS.len() as i32);
    for c in CHANNELS {
        p.string(c);
    }
    for v in [0, 0, width as i32, height as i32] {
        p.i32(v);
    }
    for c in 0..CHANNELS.len() {
        p.i64(c as i64);
    }
    for _ in CHANNELS {
        p.i64(CHANNELS.len() as i64);
    }
    p.0.reserve(rgb.len() * 12);
    for c in rgb {
        for v in c.to_array() {
            p.0.extend_from_slice(&v.to_le_bytes());
        }
    }
    p.finish()
}

/// A connection to a running tev that takes frames without blocking the caller.
pub struct TevDisplay {
    frames: Option<SyncSender<Vec<u8>>>,
    sender: Option<JoinHandle<()>>,
}

impl TevDisplay {
    /// Connects to tev at `address` (`HOST:PORT`) and creates image `name`. A viewer
    /// that cannot be reached (within two seconds) is a warning on stderr and `None`.
    pub fn connect(address: &str, name: &str, width: u32, height: u32) -> Option<TevDisplay> {
        let stream = std::net::ToSocketAddrs::to_socket_addrs(address)
            .map_err(|e| e.to_string())
            .and_then(|mut addrs| addrs.next().ok_or_else(|| "no address".to_string()))
            .and_then(|a| {
                TcpStream::connect_timeout(&a, Duration::from_secs(2)).map_err(|e| e.to_string())
            })
            .and_then(|mut s| {
                s.write_all(&create_image_packet(name, width, height))
                    .map(|_| s)
                    .map_err(|e| e.to_string())
            });
        let mut stream = match stream {
            Ok(s) => s,
            Err(e) => {
                eprintln!("warning: no live view: cannot reach tev at {address}: {e}");
                return None;
            }
        };
        // One frame in flight: a frame that finds the channel full is dropped.
        let (frames, inbox) = sync_channel::<Vec<u8>>(1);
        let address = address.to_string();
        let sender = std::thread::spawn(move || {
            for frame in inbox {
                if let Err(e) = stream.write_all(&frame) {
                    eprintln!("warning: live view stopped: tev at {address}: {e}");
                    return;
                }
            }
        });
        Some(TevDisplay {
            frames: Some(frames),
            sender: Some(sender),
        })
    }

    /// Queues `film` as image `name`; returns false when the frame was dropped because
    /// the previous one is still being sent (or the viewer went away).
    pub fn send(&self, name: &str, film: &Film) -> bool {
        let Some(frames) = &self.frames else {
            return false;
        };
        match frames.try_send(film_packet(name, film)) {
            Ok(()) => true,
            Err(TrySendError::Full(_) | TrySendError::Disconnected(_)) => false,
        }
    }

    /// Sends `film` as the last frame, waiting for the frames before it (a finished
    /// render's final image must not be dropped).
    pub fn finish(mut self, name: &str, film: &Film) {
        if let Some(frames) = self.frames.take() {
            let _ = frames.send(film_packet(name, film));
        }
        if let Some(sender) = self.sender.take() {
            let _ = sender.join();
        }
    }
}

impl Drop for TevDisplay {
    fn drop(&mut self) {
        // Closing the channel ends the sender thread once it has written what it holds.
        self.frames.take();
        if let Some(sender) = self.sender.take() {
            let _ = sender.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::PixelStats;

    fn u32_at(b: &[u8], i: usize) -> u32 {
        u32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]])
    }

    #[test]
    fn create_image_is_length_prefixed_with_nul_terminated_names() {
        let p = create_image_packet("img", 5, 2);
        assert_eq!(u32_at(&p, 0) as usize, p.len());
        assert_eq!(&p[4..10], &[CREATE_IMAGE, 1, b'i', b'm', b'g', 0]);
        assert_eq!((u32_at(&p, 10), u32_at(&p, 14), u32_at(&p, 18)), (5, 2, 3));
        assert_eq!(&p[22..], b"R\0G\0B\0");
    }

    #[test]
    fn update_image_carries_interleaved_rgb_with_offsets_and_strides() {
        let mut film = Film::new(2, 1);
        film.pixels[1] = PixelStats {
            mean: Spectrum::new(1.0, 2.0, 3.0),
            ..Default::default()
        };
        let p = film_packet("a", &film);
        assert_eq!(u32_at(&p, 0) as usize, p.len());
        assert_eq!(&p[4..8], &[UPDATE_IMAGE_V3, 0, b'a', 0]);
        assert_eq!(u32_at(&p, 8), 3);
        assert_eq!(&p[12..18], b"R\0G\0B\0");
        let dims: Vec<u32> = (0..4).map(|k| u32_at(&p, 18 + 4 * k)).collect();
        assert_eq!(dims, [0, 0, 2, 1]);
        let longs: Vec<u32> = (0..6).map(|k| u32_at(&p, 34 + 8 * k)).collect();
        assert_eq!(longs, [0, 1, 2, 3, 3, 3]);
        let floats: Vec<f32> = (0..6)
            .map(|k| f32::from_bits(u32_at(&p, 82 + 4 * k)))
            .collect();
        assert_eq!(floats, [0.0, 0.0, 0.0, 1.0, 2.0, 3.0]);
        assert_eq!(p.len(), 82 + 24);
    }

    #[test]
    fn an_unreachable_viewer_is_none() {
        // Port 1 on localhost: nothing listens there in a test environment.
        assert!(TevDisplay::connect("127.0.0.1:1", "x", 1, 1).is_none());
        assert!(TevDisplay::connect("not an address", "x", 1, 1).is_none());
    }
}
