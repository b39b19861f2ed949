//! `lightlab warp`.
