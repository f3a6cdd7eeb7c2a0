//! Every constant of the algorithm, as a setting. The defaults are the Quality preset (the measured accurate mode);
//! `Preset::Balanced` is the FidelityFX shadow denoiser's values.

use crate::error::{Error, Result};

/// Declares every setting once: its doc, type, default, valid range (low, high, and the interval as messages and
/// the C header write it). From that one list come the `Settings` struct, its `Default`, its validation, the
/// range table the header test checks DnsrSettings against, and `for_each_setting!`, which the C conversion
/// uses so that a setting cannot be missed there.
macro_rules! declare_settings {
    ($( $(#[doc = $doc:literal])* $name:ident : $t:ty = $default:expr, [$lo:expr, $hi:expr] $range:literal; )*) => {
        /// Algorithm settings. `Settings::default()` is `Preset::Quality`, the accurate mode (docs/do-no-harm.md);
        /// `Preset::Balanced` reproduces the FidelityFX shadow denoiser. They can be changed between frames with
        /// `Context::set_settings`; every field is range-checked (NaN refused).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Settings {
            $( $(#[doc = $doc])* #[doc = concat!(" Range ", $range, ". Default ", stringify!($default), ".")] pub $name: $t, )*
        }

        impl Default for Settings {
            fn default() -> Self {
                Settings { $( $name: $default ),* }
            }
        }

        /// Every setting's valid interval, as written in messages and in both headers' docs.
        #[cfg_attr(not(test), allow(dead_code))]
        pub(crate) const RANGES: &[(&str, &str)] = &[ $( (stringify!($name), $range) ),* ];

        impl Settings {
            /// Checks every field against its valid range.
            pub fn validate(&self) -> Result<()> {
                $(
                    let value = self.$name as f64;
                    if !(value >= $lo as f64 && value <= $hi as f64) {
                        return Err(Error::InvalidSetting { name: stringify!($name), value, range: $range });
                    }
                )*
                Ok(())
            }
        }

        /// Calls `$m!` with every setting's field name.
        macro_rules! for_each_setting {
            ($m:ident) => { $m!($($name),*) };
        }
        pub(crate) use for_each_setting;
    };
}

declare_settings! {
    /// Number of a-trous filter passes, with tap steps 1, 2, 4, 8 pixels.
    filter_passes: u32 = 2, [1, MAX_FILTER_PASSES] "[1, 4]";
    /// Relative depth change that counts as disocclusion when the surface faces the camera.
    disocclusion_threshold_facing: f32 = 0.01, [0.0, 10.0] "[0, 10]";
    /// Relative depth change that counts as disocclusion at grazing angles.
    disocclusion_threshold_grazing: f32 = 0.1, [0.0, 10.0] "[0, 10]";
    /// Exponent of (1 - N.V) that blends between the two thresholds.
    disocclusion_angle_exponent: f32 = 8.0, [0.0, 64.0] "[0, 64]";
    /// Falloff of the 17x17 local-moment Gaussian: w(i) = exp(-falloff * i^2 / 81).
    spatial_falloff: f32 = 3.0, [0.0, 100.0] "[0, 100]";
    /// Width of the history clamp window around the local mean, in local standard deviations.
    history_clamp_sigmas: f32 = 0.5, [0.0, 16.0] "[0, 16]";
    /// History rejection: the sample count is multiplied by exp(-d^2 / falloff), d the history's distance from
    /// the local mean in clamp widths.
    history_rejection_falloff: f32 = 20.0, [1e-3, 1e6] "[1e-3, 1e6]";
    /// Floor of the clamp width used in the rejection distance.
    history_rejection_min_sigma: f32 = 0.001, [1e-6, 1.0] "[1e-6, 1]";
    /// A pixel whose last n >= this-many samples were identical is clamped to within 3/n of them instead of to the
    /// local 17x17 distribution, and its history is not rejected: the input already resolves it (a hard shadow
    /// edge), and the local distribution, which straddles the edge, would pull it towards the edge's mean.
    /// 0 turns this off (the FidelityFX behaviour).
    stable_history_samples: f32 = 8.0, [0.0, MAX_SAMPLE_RUN as f32] "[0, 127]";
    /// After a stable run (`stable_history_samples`), this many samples of the other value in a row, or the first
    /// one where the local 17x17 mean is within 0.5 of it, restart the pixel's history at the local mean: the
    /// shadow moved over the pixel, with or without motion vectors. Whole samples (a fraction is dropped); 0 turns
    /// this off; it needs `stable_history_samples` > 0.
    history_flip_samples: f32 = 3.0, [0.0, 16.0] "[0, 16]";
    /// A stable pixel (`stable_history_samples`) whose last n >= this-many samples were identical and whose
    /// moments hold no other sample is converged (variance 0); where at least half of its 3x3 receivers are
    /// converged too, the filter passes it through as its run's value. The 1-spp input then resolves it (a hard
    /// shadow, a face turned from the light, a crease, a thin stripe), and the 17x17 moments and the filter taps,
    /// which straddle its edges, silhouettes and the sky, could only move it away; a lone run in a penumbra is
    /// filtered as before. Not where `moving_shadow_sigmas` finds that the shadow moved over a still pixel: its run
    /// restarted when the shadow passed, and a short run there is as often a penumbra's. Under a moving camera, a
    /// receiver beside the sky whose footprint's texels of the other value held it for this many samples or more,
    /// and two of whose 8 neighbours share its sample, takes its sample as it is (a resolved silhouette,
    /// docs/do-no-harm.md). 0 turns this off (the FidelityFX behaviour);
    /// converged pixels need `stable_history_samples` > 0, resolved silhouettes do not.
    converged_samples: f32 = 8.0, [0.0, MAX_SAMPLE_RUN as f32] "[0, 127]";
    /// A shadow that moved over a still surface (an occluder moving without motion vectors on the receiver): where a
    /// pixel does not move (its motion vector under 0.01 px) and this frame's samples around its 8x4 tile (one tile
    /// either side, two above and below: 24x20 px) lie further from last frame's accumulated means there than this
    /// many standard deviations (their Bernoulli spread, plus two samples), its history is clamped to
    /// `moving_history_clamp_sigmas` instead of `history_clamp_sigmas`: the history still holds where the shadow
    /// was. 3 takes `make accuracy`'s moving family from 0.51 to 0.33 of its input's error (its still twins
    /// unchanged, measured with three filter passes) for 0.07 ms more classification at 4K on an H200; on in Quality
    /// and Fast since Quality's third filter pass went, which paid for it (docs/do-no-harm.md, "A shadow moving over
    /// a still surface"). 0 turns it off (its pipelines compile it out: `DNSR_SPEC_MOVING_SHADOWS`; Balanced); it
    /// needs the run features (`stable_history_samples` or `converged_samples` > 0).
    moving_shadow_sigmas: f32 = 3.0, [0.0, 16.0] "[0, 16]";
    /// The history clamp's width, in local standard deviations, where the shadow moved (`moving_shadow_sigmas`).
    moving_history_clamp_sigmas: f32 = 0.1, [0.0, 16.0] "[0, 16]";
    /// Hard tiles told by time, without penumbra guidance: a world point in a hard shadow keeps its value from frame
    /// to frame, one in a penumbra changes it at random. Each 8x4 tile counts the frames since one of its receivers'
    /// samples contradicted last frame (under a still camera, the sample differs from its texel's last sample; under
    /// a moving one, from the last samples of every texel of its footprint and of the 3x3 texels around it, or every
    /// texel of the footprint held both values, at least a quarter each, over 8 samples or more). Where the 3x3
    /// tiles around a receiver's tile all counted this many frames or more, and the receiver does not contradict
    /// (disoccluded or not), its output is its sample of this frame (a hard or nearly hard shadow that the history and
    /// the filter would blur under a moving camera). Where a penumbra shows no contradiction the output is its input,
    /// never worse than it. 0 turns this off (the FidelityFX behaviour); it needs the run features
    /// (`stable_history_samples` or `converged_samples` > 0). docs/do-no-harm.md, "Hard tiles told by time".
    hard_tile_frames: f32 = 6.0, [0.0, MAX_QUIET_FRAMES] "[0, 255]";
    /// Penumbra guidance only (a dispatch with hit distances): where the blockers near a tile cast a penumbra
    /// narrower than this many pixels either side of its edge (from their mean hit distance, the light's angular
    /// size and the receiver's depth) and lie at least two pixel footprints away (under a light of angular size 0:
    /// blockers at any distance), or where no blocker is known within +-8 px of the tile (its shadowed pixels face
    /// away from the light), a receiver's output is its sample of this frame, neither accumulated nor filtered. One ray then resolves the pixel (a hard light, a
    /// distant sun's blocker); accumulating it under a moving camera blurs edges and loses sub-pixel features (a
    /// wire's shadow), and where the estimate errs the output is the input, never worse. The price is on a still
    /// camera, whose accumulation would resolve the few pixels inside such a penumbra. 0 turns this off (the
    /// FidelityFX behaviour).
    hard_penumbra_pixels: f32 = 0.25, [0.0, 16.0] "[0, 16]";
    /// Below this many accumulated samples the variance is boosted (raised to the spatial variance and
    /// multiplied by the missing samples), except on a pixel whose run is stable (`stable_history_samples`).
    variance_boost_samples: f32 = 16.0, [0.0, 1024.0] "[0, 1024]";
    /// Sample count from which the history gets its full weight.
    full_history_samples: f32 = 8.0, [1.0, 1024.0] "[1, 1024]";
    /// Weight of the current frame once the history is fully trusted.
    min_current_weight: f32 = 0.1, [1e-3, 1.0] "[1e-3, 1]";
    /// Bound on the temporal sample count, so the moments cannot grow without limit. (The moments' 9-bit count
    /// holds whole counts exactly up to 64 and even ones up to 128.)
    max_history_samples: f32 = 32.0, [2.0, MAX_HISTORY_SAMPLES] "[2, 128]";
    /// Weight of the cross taps of the 3x3 kernel relative to the center (corners get its square).
    kernel_cross_weight: f32 = 0.5, [0.0, 1.0] "[0, 1]";
    /// Exponent of the normal edge stop max(dot(Nc, Nq), 0)^p.
    normal_power: f32 = 32.0, [0.0, 256.0] "[0, 256]";
    /// Output contrast: the last pass writes pow(mean, max(contrast - variance, 1)); 1 = none.
    output_contrast: f32 = 1.0, [1.0, 4.0] "[1, 4]";
    /// Floor of the shadow edge stop's standard deviation, keeps exp(-|c - n| / sigma) finite.
    min_shadow_sigma: f32 = 1e-4, [1e-6, 1.0] "[1e-6, 1]";
    /// The first filter pass weighs its taps by each receiver's geometric normal (the plane through its nearer
    /// neighbour along each axis, from the depth and `view_projection_inverse`) where that lies within this many
    /// degrees of the G-buffer's normal: a normal map tilts normals by tens of degrees within a few pixels of one
    /// plane, and the normal edge stop then stops the filter. Past it, and where an axis has no receiver neighbour,
    /// the G-buffer's normal stays (a feature of 1-2 px, whose neighbours' depths give another surface's plane; a
    /// crease). 0 turns this off (the FidelityFX behaviour). Only with the run features (`stable_history_samples` or
    /// `converged_samples` > 0, as in Fast and Quality): the first pass compiles the code under the specialization
    /// constant that gates them, so that Balanced does not pay its registers. docs/do-no-harm.md, "Normal-mapped
    /// normals".
    geometric_normal_degrees: f32 = 53.0, [0.0, 89.0] "[0, 89]";
}

/// Named settings chosen from the accuracy measurements in docs/accuracy.md (`make accuracy`) and the scene family
/// of docs/do-no-harm.md: on the truth-known sequences Balanced measures a mean RMSE of 0.060, Fast 0.022, Quality 0.019
/// with a shadow-jump lag of 1 frame instead of 14.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// Quality's knobs with one filter pass: the cheapest setting that keeps Quality's do-no-harm features (runs,
    /// converged pixels, hard penumbrae). On the scene family it is as often worse than its input as Quality and
    /// its mean error is lower (small objects lose less to a single pass); on wide penumbrae its error is higher
    /// (docs/do-no-harm.md, docs/accuracy.md).
    Fast,
    /// The FidelityFX shadow denoiser's values (its output, for engines that need the old look): 3 filter
    /// passes, 5% current-frame weight, output contrast 1.2, cross-tap weight 2/3, none of the run-based features.
    Balanced,
    /// The default (`Settings::default()`): the measured best knobs combined. 2 filter passes (a third's 4-px step
    /// blurs hard edges and thin features on scenes it has never seen, and costs 0.25 ms at 4K on an H200:
    /// docs/do-no-harm.md), 10% current-frame weight, no output contrast, cross tap weight 0.5, history of pixels with
    /// 8 identical samples in a row clamped to their run and restarted after 3 samples of the other value (1 where the
    /// neighbourhood agrees; see docs/accuracy.md for why each), pixels with 8 identical samples in a row converged
    /// (passed through the filter among converged neighbours; docs/do-no-harm.md), a shadow that moved over a still
    /// surface clamped to its new samples (`moving_shadow_sigmas`), without penumbra guidance the local statistics
    /// taken over the pixel's own surface (creases, fins and the sky left out: docs/do-no-harm.md) and hard tiles told
    /// by time, and, with penumbra guidance, pixels under a penumbra narrower than a quarter of a pixel either side
    /// output as sampled.
    Quality,
}

impl Settings {
    /// The settings of a preset.
    pub fn preset(preset: Preset) -> Settings {
        let quality = Settings::default();
        let balanced = Settings {
            filter_passes: 3,
            min_current_weight: 0.05,
            output_contrast: 1.2,
            kernel_cross_weight: 2.0 / 3.0,
            stable_history_samples: 0.0,
            history_flip_samples: 0.0,
            converged_samples: 0.0,
            hard_penumbra_pixels: 0.0,
            hard_tile_frames: 0.0,
            moving_shadow_sigmas: 0.0,
            geometric_normal_degrees: 0.0,
            ..quality
        };
        match preset {
            Preset::Fast => Settings { filter_passes: 1, ..quality },
            Preset::Balanced => balanced,
            Preset::Quality => quality,
        }
    }
}

impl Settings {
    /// The cosine `geometric_normal_degrees` allows, as the first filter pass reads it (2: off, no normal is that
    /// close; also without the run features, whose specialization constant compiles the code in).
    pub(crate) fn geometric_normal_min_cos(&self) -> f32 {
        if self.geometric_normal_degrees > 0.0 && self.uses_runs() {
            self.geometric_normal_degrees.to_radians().cos()
        } else {
            2.0
        }
    }

    /// Whether a feature built on runs of identical samples is on (stable history or converged pixels): the
    /// classification pipelines specialized with DNSR_SPEC_STABLE_HISTORY run them (and, with a hit mask and without
    /// penumbra guidance, the surface window). Public (hidden) for dnsr-bench's byte model only.
    #[doc(hidden)]
    pub fn uses_runs(&self) -> bool {
        self.stable_history_samples > 0.0 || self.converged_samples > 0.0
    }

    /// Whether classification tells a shadow that moved over a still surface (`moving_shadow_sigmas` > 0, with the
    /// run features): its pipelines are specialized with DNSR_SPEC_MOVING_SHADOWS.
    pub(crate) fn tells_moving_shadows(&self) -> bool {
        self.moving_shadow_sigmas > 0.0 && self.uses_runs()
    }
}

/// Largest number of filter passes. The last one's step (8 px) stays within a block (`GROUP`).
pub const MAX_FILTER_PASSES: u32 = 4;

/// A tile's count of quiet frames stops here (`Settings::hard_tile_frames`' upper bound).
pub(crate) const MAX_QUIET_FRAMES: u32 = 255;

/// Longest run of identical samples a pixel's moments record (moments.w: +n lit, -n shadowed); a cleared tile
/// records the longest run. Bounds the run settings. Generated into GLSL. The moments store twice the run in 9
/// bits (shaders/dnsr_storage.glsl).
pub(crate) const MAX_SAMPLE_RUN: u32 = ((1 << (crate::packing::MOMENTS_RUN_BITS - 1)) - 1) / 2;
const _: () = assert!(MAX_SAMPLE_RUN == 127);

/// Largest `max_history_samples`: the moments' count (`packing::COUNT_MANTISSA_BITS`) holds whole counts up to 64,
/// steps by 2 up to 128 and by 4 from there, where adding a sample would no longer change it.
const MAX_HISTORY_SAMPLES: f32 = (1u32 << (crate::packing::COUNT_MANTISSA_BITS + 2)) as f32;

/// Checks a filter pass count (outside a `Settings`, e.g. for `memory_requirements`).
pub(crate) fn check_filter_passes(passes: u32) -> Result<()> {
    Settings { filter_passes: passes, ..Settings::default() }.validate()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_is_valid_and_quality_is_the_default() {
        for p in [Preset::Fast, Preset::Balanced, Preset::Quality] {
            Settings::preset(p).validate().unwrap();
        }
        assert_eq!(Settings::preset(Preset::Quality), Settings::default());
        // Balanced is FidelityFX: none of the run-based features, which FidelityFX does not have.
        let b = Settings::preset(Preset::Balanced);
        assert!(!b.uses_runs() && b.hard_penumbra_pixels == 0.0 && b.hard_tile_frames == 0.0 && b.moving_shadow_sigmas == 0.0 && b.output_contrast == 1.2);
    }

    /// The first pass compiles geometric normals under the run features' specialization constant, so the setting the
    /// shader and the CPU reference read must say "off" without them, whatever `geometric_normal_degrees` asks.
    #[test]
    fn geometric_normals_need_the_run_features() {
        let quality = Settings::preset(Preset::Quality);
        assert!(quality.uses_runs() && quality.geometric_normal_min_cos() <= 1.0);
        let balanced = Settings { geometric_normal_degrees: 53.0, ..Settings::preset(Preset::Balanced) };
        assert!(!balanced.uses_runs());
        assert!(balanced.geometric_normal_min_cos() > 1.0);
    }
}
