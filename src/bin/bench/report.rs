//! Summaries of the runs, bench.json and bench.md.

use super::copy::CopyResult;
use super::device::DeviceInfo;
use super::json::Json;
use super::model::{model_json, model_markdown, pass_bytes, Fed, PassId, PixelCounts};
use super::run::{ConfigRun, WarmupDone, SUBMISSION};
use super::scenes::{HostFormats, SceneId, ALL_SCENES};
use super::stats::{max, mean, median, min, percentile};
use dnsr::{Precision, Preset, ShadowInput};

pub struct PassSummary {
    pub id: PassId,
    pub median_ms: f64,
    pub p95_ms: f64,
    pub read_bytes: f64,
    pub write_bytes: f64,
}

impl PassSummary {
    pub fn bytes(&self) -> f64 {
        self.read_bytes + self.write_bytes
    }
}

pub struct Summary {
    pub size: (u32, u32),
    pub scene: SceneId,
    pub preset: Preset,
    pub precision: Precision,
    pub frames: usize,
    pub filter_passes: u32,
    pub passes: Vec<PassSummary>,
    pub total: PassSummary,
    pub total_ms: Vec<f64>,
    pub record_us: Vec<f64>,
    pub record_us_untimed: Vec<f64>,
    /// Its records back to back, never submitted (caches and clocks warm).
    pub record_us_warm: Vec<f64>,
    pub memory_bytes: u64,
    pub persistent_bytes: u64,
    pub counts: PixelCounts,
    pub coverage: [f64; 4],
    pub warmup: WarmupDone,
    /// Lights denoised per frame (one record_lights call when more than one).
    pub lights: usize,
    /// The G-buffer formats fed.
    pub host: HostFormats,
    /// The shadow input fed.
    pub input: ShadowInput,
    /// ConfigRun::pipelines.
    pub pipelines: Vec<(&'static str, Vec<(String, String)>)>,
}

pub fn preset_name(p: Preset) -> &'static str {
    match p {
        Preset::Fast => "fast",
        Preset::Balanced => "balanced",
        Preset::Quality => "quality",
    }
}

pub fn precision_name(p: Precision) -> &'static str {
    match p {
        Precision::Fp32 => "fp32",
        Precision::Fp16 => "fp16",
    }
}

impl Summary {
    pub fn new(
        size: (u32, u32),
        scene: SceneId,
        preset: Preset,
        precision: Precision,
        run: ConfigRun,
        coverage: [f64; 4],
        lights: usize,
        fed: Fed,
    ) -> Summary {
        let n = run.filter_passes;
        let ids = [PassId::Prepare, PassId::TileClassification].into_iter().chain((0..n).map(PassId::Filter));
        let passes: Vec<PassSummary> = ids
            .map(|id| {
                let ms: Vec<f64> = run
                    .timings
                    .iter()
                    .map(|t| match id {
                        PassId::Prepare => t.prepare_ms,
                        PassId::TileClassification => t.tile_classification_ms,
                        PassId::Filter(k) => t.filter_ms[k as usize],
                    })
                    .collect();
                // Every light moves light 0's bytes (its pixel classes stand for all of them).
                let (read_bytes, write_bytes) = pass_bytes(id, n, precision, &run.counts, fed.with_preset(preset));
                let (read_bytes, write_bytes) = (read_bytes * lights as f64, write_bytes * lights as f64);
                PassSummary { id, median_ms: median(&ms), p95_ms: percentile(&ms, 95.0), read_bytes, write_bytes }
            })
            .collect();
        let total_ms: Vec<f64> = run.timings.iter().map(|t| t.total_ms).collect();
        let total = PassSummary {
            id: PassId::Prepare,
            median_ms: median(&total_ms),
            p95_ms: percentile(&total_ms, 95.0),
            read_bytes: passes.iter().map(|p| p.read_bytes).sum(),
            write_bytes: passes.iter().map(|p| p.write_bytes).sum(),
        };
        Summary {
            size,
            scene,
            preset,
            precision,
            frames: run.timings.len(),
            filter_passes: n,
            passes,
            total,
            total_ms,
            record_us: run.record_us,
            record_us_untimed: run.record_us_untimed,
            record_us_warm: run.record_us_warm,
            memory_bytes: run.memory_bytes,
            persistent_bytes: run.persistent_bytes,
            counts: run.counts,
            coverage,
            warmup: run.warmup,
            lights,
            host: fed.host,
            input: fed.input,
            pipelines: run.pipelines,
        }
    }

    /// The preset, and the light count where more than one light is denoised per frame.
    fn preset_cell(&self) -> String {
        match self.lights {
            1 => preset_name(self.preset).to_string(),
            n => format!("{}, {n} lights", preset_name(self.preset)),
        }
    }

    fn pixels(&self) -> f64 {
        self.size.0 as f64 * self.size.1 as f64
    }
}

/// Achieved GB/s and time over the copy roofline (time / (bytes / copy bandwidth)).
fn rates(bytes: f64, ms: f64, copy: &CopyResult) -> (f64, f64) {
    let gbps = bytes / (ms * 1e-3) / 1e9;
    let roofline_ms = bytes / copy.bytes_per_s() * 1e3;
    (gbps, ms / roofline_ms)
}

fn pass_json(name: &str, p: &PassSummary, copy: &CopyResult) -> Json {
    let (gbps, ratio) = rates(p.bytes(), p.median_ms, copy);
    Json::obj([
        ("pass", name.into()),
        ("median_ms", p.median_ms.into()),
        ("p95_ms", p.p95_ms.into()),
        ("model_read_bytes", p.read_bytes.into()),
        ("model_write_bytes", p.write_bytes.into()),
        ("achieved_gbps", gbps.into()),
        ("roofline_ratio", ratio.into()),
    ])
}

pub struct Report<'a> {
    pub device: &'a DeviceInfo,
    pub commit: (String, &'static str, Option<bool>),
    pub command_line: String,
    pub date: String,
    pub warmup: usize,
    pub warmup_ms: usize,
    pub frames: usize,
    pub copy: &'a CopyResult,
    pub results: &'a [Summary],
    pub skipped: &'a [String],
    pub wall_s: f64,
    /// The G-buffer formats fed (every result's).
    pub host: HostFormats,
    /// The shadow input fed (every result's).
    pub input: ShadowInput,
}

impl Report<'_> {
    pub fn json(&self) -> Json {
        let c = self.copy;
        let results = self
            .results
            .iter()
            .map(|s| {
                let [sky, lit, shadowed, penumbra] = s.coverage;
                let mut total = pass_json("total", &s.total, c);
                if let Json::Obj(m) = &mut total {
                    m.insert(3, ("min_ms".into(), min(&s.total_ms).into()));
                    m.insert(4, ("max_ms".into(), max(&s.total_ms).into()));
                    m.insert(5, ("mean_ms".into(), mean(&s.total_ms).into()));
                }
                Json::obj([
                    ("width", s.size.0.into()),
                    ("height", s.size.1.into()),
                    ("scene", s.scene.id().into()),
                    ("preset", preset_name(s.preset).into()),
                    ("lights", (s.lights as f64).into()),
                    ("precision", precision_name(s.precision).into()),
                    ("filter_passes", s.filter_passes.into()),
                    ("frames", s.frames.into()),
                    (
                        "warmup",
                        Json::obj([
                            ("frames", s.warmup.frames.into()),
                            ("ms", s.warmup.ms.into()),
                            ("stable", s.warmup.stable.into()),
                        ]),
                    ),
                    ("passes", Json::Arr(s.passes.iter().map(|p| pass_json(&p.id.name(), p, c)).collect())),
                    ("total", total),
                    ("model_bytes_per_pixel", (s.total.bytes() / s.pixels()).into()),
                    (
                        "record_cpu_us",
                        Json::obj([("median", median(&s.record_us).into()), ("p95", percentile(&s.record_us, 95.0).into())]),
                    ),
                    (
                        "record_cpu_us_timestamps_off",
                        Json::obj([
                            ("median", median(&s.record_us_untimed).into()),
                            ("p95", percentile(&s.record_us_untimed, 95.0).into()),
                        ]),
                    ),
                    (
                        "record_cpu_us_back_to_back",
                        Json::obj([
                            ("median", median(&s.record_us_warm).into()),
                            ("p95", percentile(&s.record_us_warm, 95.0).into()),
                        ]),
                    ),
                    ("memory_bytes", s.memory_bytes.into()),
                    ("memory_bytes_per_pixel", (s.memory_bytes as f64 / s.pixels()).into()),
                    ("persistent_memory_bytes", s.persistent_bytes.into()),
                    ("pixel_classes", s.counts.to_json()),
                    (
                        "scene_coverage",
                        Json::obj([
                            ("sky", sky.into()),
                            ("lit", lit.into()),
                            ("shadowed", shadowed.into()),
                            ("penumbra", penumbra.into()),
                        ]),
                    ),
                    ("total_ms_samples", s.total_ms.clone().into()),
                    (
                        "pipelines",
                        Json::Arr(
                            s.pipelines
                                .iter()
                                .map(|(name, stats)| {
                                    Json::obj([("pipeline", (*name).into()), ("statistics", Json::Obj(stats.iter().map(|(k, v)| (k.clone(), v.as_str().into())).collect()))])
                                })
                                .collect(),
                        ),
                    ),
                ])
            })
            .collect();
        Json::obj([
            ("schema", "dnsr-bench/1".into()),
            ("date_utc", self.date.clone().into()),
            ("command_line", self.command_line.clone().into()),
            ("commit", self.commit.0.clone().into()),
            ("commit_source", self.commit.1.into()),
            ("commit_dirty", self.commit.2.into()),
            ("device", self.device.to_json()),
            (
                "method",
                Json::obj([
                    ("submission", SUBMISSION.into()),
                    ("warmup_min_frames", self.warmup.into()),
                    ("warmup_min_ms", self.warmup_ms.into()),
                    ("timed_frames", self.frames.into()),
                    ("statistics", "median (mean of the two middle samples for an even count) and p95 (nearest rank) over the timed frames".into()),
                    ("output_format", "R16_SFLOAT".into()),
                    (
                        "host_formats",
                        Json::obj([
                            ("hit_mask", "R32_UINT".into()),
                            ("depth", format!("{:?}", self.host.depth()).into()),
                            ("velocity", format!("{:?}", self.host.velocity()).into()),
                            ("normals", format!("{:?}", self.host.normals()).into()),
                        ]),
                    ),
                    ("roofline_ratio", "pass GPU time / (model bytes / copy bandwidth); 1 = as fast as a copy of the same bytes".into()),
                ]),
            ),
            (
                "copy_bandwidth",
                Json::obj([
                    ("kernel", "shaders/bench/copy.comp: storage buffer -> storage buffer, 16 B per invocation".into()),
                    ("buffer_bytes", c.buffer_bytes.into()),
                    ("moved_bytes_per_run", c.moved_bytes().into()),
                    ("dispatches_per_run", c.chunks.into()),
                    ("runs", c.runs_ms.len().into()),
                    ("median_ms", c.median_ms().into()),
                    ("gbps_median", c.gbps(c.median_ms()).into()),
                    ("gbps_best", c.gbps(min(&c.runs_ms)).into()),
                    ("gbps_worst", c.gbps(max(&c.runs_ms)).into()),
                    ("runs_ms", c.runs_ms.clone().into()),
                ]),
            ),
            ("byte_model", model_json(Fed::documented(self.host, self.input))),
            (
                "scenes",
                Json::Arr(
                    ALL_SCENES
                        .iter()
                        .map(|s| Json::obj([("id", s.id().into()), ("name", s.name().into()), ("description", s.description().into())]))
                        .collect(),
                ),
            ),
            ("skipped", self.skipped.to_vec().into()),
            ("results", Json::Arr(results)),
            ("bench_wall_s", self.wall_s.into()),
        ])
    }

    pub fn markdown(&self) -> String {
        let c = self.copy;
        let d = self.device;
        let mut s = String::from("# dnsr-bench\n\n");
        s += &format!("- Device: {} (Vulkan {}, driver {})\n", d.name, d.api_version, d.driver());
        let dirty = match self.commit.2 {
            Some(true) => " (tracked files modified)",
            _ => "",
        };
        s += &format!("- Commit: {}{dirty}\n", self.commit.0);
        s += &format!("- Command: `{}`\n", self.command_line);
        s += &format!("- Date: {}\n", self.date);
        s += &format!(
            "- Copy bandwidth (read + write, shaders/bench/copy.comp, {} MiB per buffer, median of {}): {:.1} GB/s\n",
            c.buffer_bytes >> 20,
            c.runs_ms.len(),
            c.gbps(c.median_ms())
        );
        let stable = self.results.iter().filter(|r| r.warmup.stable).count();
        let warmup = if self.warmup_ms == 0 {
            format!("warm-up of exactly {} frames (no time minimum)", self.warmup)
        } else {
            let n = self.results.len();
            let capped = if stable == n { String::new() } else { format!(", {} stopped at 5x {} ms", n - stable, self.warmup_ms) };
            format!(
                "warm-up of at least {} frames and {} ms, then until stable ({stable} of {n} rows passed the 2% test{capped})",
                self.warmup, self.warmup_ms
            )
        };
        s += &format!(
            "- Frames: {warmup}; then median / p95 of {} timed frames per row{}\n",
            self.frames,
            if self.frames < 200 { " (fewer than 200: not for quoting)" } else { "" }
        );
        s += &format!("- Submission: {SUBMISSION}\n");
        let h = self.host;
        s += &format!(
            "- Inputs: hit mask R32_UINT, depth {:?}, velocity {:?}, normals {:?} (decoded with unpack mul {}, add {}); output R16_SFLOAT\n",
            h.depth(),
            h.velocity(),
            h.normals(),
            h.normals_unpack().0,
            h.normals_unpack().1
        );
        for sk in self.skipped {
            s += &format!("- Skipped: {sk}\n");
        }
        s += "\nTimes in ms (GPU timestamps). GB/s and x roofline use the byte model below: x roofline = time / (model bytes / copy bandwidth). \
              Record CPU = median wall time of Context::record_shadows. Memory = Context::memory_bytes per pixel, of which kept = Context::persistent_memory_bytes (the rest is transient: written and read within one record).\n";

        for precision in [Precision::Fp32, Precision::Fp16] {
            let rows: Vec<&Summary> = self.results.iter().filter(|r| r.precision == precision).collect();
            if rows.is_empty() {
                continue;
            }
            let filters = rows.iter().map(|r| r.filter_passes).max().unwrap_or(0);
            s += &format!("\n## {}\n\n", precision_name(precision));
            s += "| size | scene | preset | prepare | classification |";
            for k in 0..filters {
                s += &format!(" filter {k} |");
            }
            s += " total median | total p95 | GB/s | x roofline | record CPU µs | record CPU µs, no timestamps | record CPU µs, back to back | memory B/px | kept B/px |\n|---|---|---|---|---|";
            s += &"---|".repeat(filters as usize);
            s += "---|---|---|---|---|---|---|---|---|\n";
            for r in &rows {
                let (gbps, ratio) = rates(r.total.bytes(), r.total.median_ms, c);
                s += &format!("| {}x{} | {} | {} |", r.size.0, r.size.1, r.scene.name(), r.preset_cell());
                for k in 0..2 + filters as usize {
                    match r.passes.get(k) {
                        Some(p) => s += &format!(" {:.3} |", p.median_ms),
                        None => s += " - |",
                    }
                }
                s += &format!(
                    " {:.3} | {:.3} | {} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |\n",
                    r.total.median_ms,
                    r.total.p95_ms,
                    fmt_gbps(gbps),
                    fmt_ratio(ratio),
                    median(&r.record_us),
                    median(&r.record_us_untimed),
                    median(&r.record_us_warm),
                    r.memory_bytes as f64 / r.pixels(),
                    r.persistent_bytes as f64 / r.pixels()
                );
            }
            s += &format!("\n### {} per pass: model MB, achieved GB/s, x roofline\n\n", precision_name(precision));
            s += "| size | scene | preset | prepare | classification |";
            for k in 0..filters {
                s += &format!(" filter {k} |");
            }
            s += " total |\n|---|---|---|---|---|";
            s += &"---|".repeat(filters as usize);
            s += "---|\n";
            for r in &rows {
                s += &format!("| {}x{} | {} | {} |", r.size.0, r.size.1, r.scene.name(), r.preset_cell());
                for k in 0..2 + filters as usize {
                    match r.passes.get(k) {
                        Some(p) => s += &format!(" {} |", cell(p, c)),
                        None => s += " - |",
                    }
                }
                s += &format!(" {} |\n", cell(&r.total, c));
            }
        }

        s += &pipelines_markdown(self.results);
        s += "\n## Scenes\n\nPixel fractions: sky / lit / shadowed / penumbra from the generator (visibility within 0.02 of 1, of 0, in between); \
              the byte model's classes measured on the device through dnsr's debug views (first configuration of each size and scene; \
              every configuration's are in bench.json).\n\n";
        s += "| size | scene | sky | lit | shadowed | penumbra | receivers | in tiles not cleared | in groups with a tile not cleared | reusing history | model B/px (fp32 balanced) |\n";
        s += "|---|---|---|---|---|---|---|---|---|---|---|\n";
        let mut seen: Vec<((u32, u32), SceneId)> = Vec::new();
        for r in self.results {
            if seen.contains(&(r.size, r.scene)) {
                continue;
            }
            seen.push((r.size, r.scene));
            let pct = |x: f64| format!("{:.1}%", 100.0 * x);
            let all = r.counts.all.max(1.0);
            let balanced = balanced_model_bpp(r, dnsr::Settings::preset(Preset::Balanced).filter_passes, Precision::Fp32);
            s += &format!(
                "| {}x{} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.1} |\n",
                r.size.0,
                r.size.1,
                r.scene.name(),
                pct(r.coverage[0]),
                pct(r.coverage[1]),
                pct(r.coverage[2]),
                pct(r.coverage[3]),
                pct(r.counts.receivers / all),
                pct(r.counts.active / all),
                pct(r.counts.active_groups / all),
                pct(r.counts.history / all),
                balanced
            );
        }
        s += "\nScenes:\n\n";
        for sc in ALL_SCENES {
            s += &format!("- {}: {}\n", sc.name(), sc.description());
        }
        s += "\n## Byte model\n\nBytes per unit: per pixel of the class named (per tile for tiles), each texel counted once per pass. Filter passes that skip groups of two cleared tiles (pass 1, and a final pass after the first) count \"every pixel\" rows over the pixels of groups with a tile not cleared only.\n\n";
        s += &model_markdown(Fed::documented(self.host, self.input));
        s += "\nThe table is Balanced's. Fast and Quality (with a hit mask, without hit distances) run classification's surface window: its normals row covers the pixels of groups with a tile not cleared (the window's apron comes from the caches); their rows of the tables above count it so.\n";
        s
    }
}

/// Balanced's model bytes per pixel of a frame with `r`'s pixel classes and `passes` filter passes.
fn balanced_model_bpp(r: &Summary, passes: u32, precision: Precision) -> f64 {
    let ids = [PassId::Prepare, PassId::TileClassification].into_iter().chain((0..passes).map(PassId::Filter));
    ids.map(|id| {
        let (rd, wr) = pass_bytes(id, passes, precision, &r.counts, Fed::documented(r.host, r.input));
        rd + wr
    })
    .sum::<f64>()
        / r.counts.all.max(1.0)
}

fn cell(p: &PassSummary, c: &CopyResult) -> String {
    let (gbps, ratio) = rates(p.bytes(), p.median_ms, c);
    let mb = p.bytes() / 1e6;
    format!("{mb:.prec$} MB, {} GB/s, {}", fmt_gbps(gbps), fmt_ratio(ratio), prec = if mb < 10.0 { 2 } else { 1 })
}

fn fmt_gbps(x: f64) -> String {
    if !x.is_finite() {
        "-".into()
    } else if x >= 100.0 {
        format!("{x:.0}")
    } else {
        format!("{x:.2}")
    }
}

fn fmt_ratio(x: f64) -> String {
    if !x.is_finite() {
        "-".into()
    } else if x >= 10.0 {
        format!("{x:.0}x")
    } else {
        format!("{x:.2}x")
    }
}

/// The driver's statistics of every pipeline a preset ran, once per precision, preset and input (the first row
/// that ran them): on NVIDIA the register count, which sets how many invocations a multiprocessor holds.
fn pipelines_markdown(results: &[Summary]) -> String {
    let mut seen: Vec<(Precision, String)> = Vec::new();
    let mut names: Vec<&str> = Vec::new();
    let mut rows: Vec<(&Summary, &str, &[(String, String)])> = Vec::new();
    for r in results.iter().filter(|r| !r.pipelines.is_empty()) {
        if seen.contains(&(r.precision, r.preset_cell())) {
            continue;
        }
        seen.push((r.precision, r.preset_cell()));
        for (pipeline, stats) in &r.pipelines {
            for (name, _) in stats {
                if !names.contains(&name.as_str()) {
                    names.push(name);
                }
            }
            rows.push((r, pipeline, stats));
        }
    }
    if rows.is_empty() {
        return String::new();
    }
    let mut s = String::from(
        "\n## Pipelines\n\nThe driver's statistics of each pipeline as the preset's frames ran it (VK_KHR_pipeline_executable_properties, \
         `Context::pipeline_statistics`), first row of each precision and preset.\n\n| precision | preset | pipeline |",
    );
    for n in &names {
        s += &format!(" {n} |");
    }
    s += &format!("\n|---|---|---|{}\n", "---|".repeat(names.len()));
    for (r, pipeline, stats) in rows {
        s += &format!("| {} | {} | {pipeline} |", precision_name(r.precision), r.preset_cell());
        for n in &names {
            s += &format!(" {} |", stats.iter().find(|(k, _)| k == n).map_or("-", |(_, v)| v.as_str()));
        }
        s += "\n";
    }
    s
}
