//! Every constant of the algorithm, as a setting whose default is the FidelityFX value.

use crate::constants::FrameConstants;
use crate::error::{Error, Result};

/// Algorithm settings. `Settings::default()` reproduces the FidelityFX shadow denoiser. They can be changed
/// between frames with `Context::set_settings`; every field is range-checked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Number of a-trous filter passes, with tap steps 1, 2, 4, 8 pixels. Range [1, 4]. Default 3.
    pub filter_passes: u32,
    /// Relative depth change that counts as disocclusion when the surface faces the camera. Range [0, 10]. Default 0.01.
    pub disocclusion_threshold_facing: f32,
    /// Relative depth change that counts as disocclusion at grazing angles. Range [0, 10]. Default 0.1.
    pub disocclusion_threshold_grazing: f32,
    /// Exponent of (1 - N.V) that blends between the two thresholds. Range [0, 64]. Default 8.
    pub disocclusion_angle_exponent: f32,
    /// Falloff of the 17x17 local-moment Gaussian: w(i) = exp(-falloff * i^2 / 81). Range [0, 100]. Default 3.
    pub spatial_falloff: f32,
    /// Width of the history clamp window around the local mean, in local standard deviations. Range [0, 16]. Default 0.5.
    pub history_clamp_sigmas: f32,
    /// History rejection: the sample count is multiplied by exp(-d^2 / falloff), d the history's distance from
    /// the local mean in clamp widths. Range [1e-3, 1e6]. Default 20.
    pub history_rejection_falloff: f32,
    /// Floor of the clamp width used in the rejection distance. Range [1e-6, 1]. Default 0.001.
    pub history_rejection_min_sigma: f32,
    /// Below this many accumulated samples the variance is boosted (raised to the spatial variance and
    /// multiplied by the missing samples). Range [0, 1024]. Default 16.
    pub variance_boost_samples: f32,
    /// Sample count from which the history gets its full weight. Range [1, 1024]. Default 8.
    pub full_history_samples: f32,
    /// Weight of the current frame once the history is fully trusted. Range [1e-3, 1]. Default 0.05.
    pub min_current_weight: f32,
    /// Bound on the temporal sample count, so the moments cannot grow without limit. Range [2, 4096]. Default 32.
    pub max_history_samples: f32,
    /// Weight of the cross taps of the 3x3 kernel relative to the center (corners get its square). Range [0, 1]. Default 2/3.
    pub kernel_cross_weight: f32,
    /// Exponent of the normal edge stop max(dot(Nc, Nq), 0)^p. Range [0, 256]. Default 32.
    pub normal_power: f32,
    /// Output contrast: the last pass writes pow(mean, max(contrast - variance, 1)). Range [1, 4]. Default 1.2 (1 = none).
    pub output_contrast: f32,
    /// Floor of the shadow edge stop's standard deviation, keeps exp(-|c - n| / sigma) finite. Range [1e-6, 1]. Default 1e-4.
    pub min_shadow_sigma: f32,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            filter_passes: 3,
            disocclusion_threshold_facing: 0.01,
            disocclusion_threshold_grazing: 0.1,
            disocclusion_angle_exponent: 8.0,
            spatial_falloff: 3.0,
            history_clamp_sigmas: 0.5,
            history_rejection_falloff: 20.0,
            history_rejection_min_sigma: 0.001,
            variance_boost_samples: 16.0,
            full_history_samples: 8.0,
            min_current_weight: 0.05,
            max_history_samples: 32.0,
            kernel_cross_weight: 2.0 / 3.0,
            normal_power: 32.0,
            output_contrast: 1.2,
            min_shadow_sigma: 1e-4,
        }
    }
}

/// Named settings chosen from the accuracy measurements in docs/accuracy.md (`make accuracy`): on its truth-known
/// sequences Fast and Balanced measure a mean RMSE of 0.060, Quality 0.047 with a shadow-jump lag of 3 frames
/// instead of 14.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// One filter pass: the cheapest setting whose error stays near the defaults'.
    Fast,
    /// The FidelityFX defaults.
    Balanced,
    /// The measured best knobs combined: 4 filter passes, 10% current-frame weight, no output contrast, cross
    /// tap weight 0.5 (see docs/accuracy.md for why each).
    Quality,
}

impl Settings {
    /// The settings of a preset.
    pub fn preset(preset: Preset) -> Settings {
        let balanced = Settings::default();
        match preset {
            Preset::Fast => Settings { filter_passes: 1, ..balanced },
            Preset::Balanced => balanced,
            Preset::Quality => Settings {
                filter_passes: 4,
                min_current_weight: 0.1,
                output_contrast: 1.0,
                kernel_cross_weight: 0.5,
                ..balanced
            },
        }
    }
}

/// Largest number of filter passes (the shared-memory apron is sized for the step of the last one).
pub const MAX_FILTER_PASSES: u32 = 4;

/// Valid range of every float setting: (field, low, high, the interval as messages and both headers write it).
/// The C header's DnsrSettings docs must quote each interval (a test checks it).
pub(crate) const FLOAT_RANGES: [(&str, f32, f32, &str); 15] = [
    ("disocclusion_threshold_facing", 0.0, 10.0, "[0, 10]"),
    ("disocclusion_threshold_grazing", 0.0, 10.0, "[0, 10]"),
    ("disocclusion_angle_exponent", 0.0, 64.0, "[0, 64]"),
    ("spatial_falloff", 0.0, 100.0, "[0, 100]"),
    ("history_clamp_sigmas", 0.0, 16.0, "[0, 16]"),
    ("history_rejection_falloff", 1e-3, 1e6, "[1e-3, 1e6]"),
    ("history_rejection_min_sigma", 1e-6, 1.0, "[1e-6, 1]"),
    ("variance_boost_samples", 0.0, 1024.0, "[0, 1024]"),
    ("full_history_samples", 1.0, 1024.0, "[1, 1024]"),
    ("min_current_weight", 1e-3, 1.0, "[1e-3, 1]"),
    ("max_history_samples", 2.0, 4096.0, "[2, 4096]"),
    ("kernel_cross_weight", 0.0, 1.0, "[0, 1]"),
    ("normal_power", 0.0, 256.0, "[0, 256]"),
    ("output_contrast", 1.0, 4.0, "[1, 4]"),
    ("min_shadow_sigma", 1e-6, 1.0, "[1e-6, 1]"),
];

/// Interval of `filter_passes`.
pub(crate) const FILTER_PASSES_RANGE: &str = "[1, 4]";

impl Settings {
    /// The float settings in `FLOAT_RANGES` order.
    fn floats(&self) -> [f32; 15] {
        [
            self.disocclusion_threshold_facing,
            self.disocclusion_threshold_grazing,
            self.disocclusion_angle_exponent,
            self.spatial_falloff,
            self.history_clamp_sigmas,
            self.history_rejection_falloff,
            self.history_rejection_min_sigma,
            self.variance_boost_samples,
            self.full_history_samples,
            self.min_current_weight,
            self.max_history_samples,
            self.kernel_cross_weight,
            self.normal_power,
            self.output_contrast,
            self.min_shadow_sigma,
        ]
    }

    /// Checks every field against its valid range.
    pub fn validate(&self) -> Result<()> {
        check_filter_passes(self.filter_passes)?;
        for (value, (name, lo, hi, range)) in self.floats().into_iter().zip(FLOAT_RANGES) {
            if !(value >= lo && value <= hi) {
                return Err(Error::InvalidSetting { name, value: value as f64, range });
            }
        }
        Ok(())
    }

    /// Fills the settings part of the per-frame constants.
    pub(crate) fn write_to(&self, c: &mut FrameConstants) {
        c.disocclusion = [
            self.disocclusion_threshold_facing,
            self.disocclusion_threshold_grazing,
            self.disocclusion_angle_exponent,
            self.history_clamp_sigmas,
        ];
        c.rejection = [self.history_rejection_falloff, self.history_rejection_min_sigma, self.variance_boost_samples, 0.0];
        c.temporal = [self.full_history_samples, self.min_current_weight, self.max_history_samples, self.spatial_falloff];
        c.filtering = [self.kernel_cross_weight, self.normal_power, self.output_contrast, self.min_shadow_sigma];
    }
}

/// Checks a filter pass count.
pub(crate) fn check_filter_passes(passes: u32) -> Result<()> {
    if (1..=MAX_FILTER_PASSES).contains(&passes) {
        Ok(())
    } else {
        Err(Error::InvalidSetting { name: "filter_passes", value: passes as f64, range: FILTER_PASSES_RANGE })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_is_valid_and_balanced_is_the_default() {
        for p in [Preset::Fast, Preset::Balanced, Preset::Quality] {
            Settings::preset(p).validate().unwrap();
        }
        assert_eq!(Settings::preset(Preset::Balanced), Settings::default());
    }
}
