//! The bytes each pass reads and writes by design: every texel a pass touches counted once (perfect reuse of
//! neighbouring taps in the caches), nothing for constants or push constants. This is the traffic of the
//! current passes, not the algorithm's floor (DESIGN.md puts that near 30-40 B/px for a whole frame).
//!
//! Each row: which pass, which resource, bytes per unit with the fp32 and the fp16 path, read or write, which
//! pixels it covers (bytes are per pixel of that class, per tile for `Tiles`), and in which filter passes it
//! applies. The rows of dnsr's internal images come from the library's state table (`dnsr::state_table::ACCESSES`,
//! src/state/table.rs: formats, accesses, pixel classes, filter passes), so a format or an access changes there,
//! once; only the rows of the host's images (whose formats are the bench's inputs) are written here. The bench
//! measures the size of every pixel class on the device (through dnsr's debug views) and multiplies out.

use super::json::Json;
use super::scenes::HostFormats;
use dnsr::state_table::{format_bytes, resource_of, Config, ACCESSES};
use dnsr::state_table::{Access, Pass, Pixels, When};
use dnsr::{Precision, ShadowInput};

/// What the bench feeds: the G-buffer's formats and the shadow input (whose images, and the moments' format, the
/// model follows).
#[derive(Clone, Copy, Debug)]
pub struct Fed {
    pub host: HostFormats,
    pub input: ShadowInput,
    /// Classification's surface window runs (a hit mask and a preset with the run features, Fast and Quality; the
    /// bench feeds no hit distances): classification reads the normals of every pixel of a group with a tile not
    /// cleared (its window's apron from the caches), not only those of its active pixels.
    pub surface_window: bool,
    /// `--host-previous`: classification reads the host's previous depth (and, with the run features, normals)
    /// where it read the depth copy (ContextCreateInfo::host_previous_gbuffer; the first filter pass writes the same
    /// word to the transient frame depth instead).
    pub host_previous: bool,
}

impl Fed {
    /// What BENCHMARKS.md's byte model table is of: the default options with these inputs, Balanced.
    pub fn documented(host: HostFormats, input: ShadowInput) -> Fed {
        Fed { host, input, surface_window: false, host_previous: false }.with_preset(dnsr::Preset::Balanced)
    }

    /// The same inputs denoised with `preset`.
    pub fn with_preset(self, preset: dnsr::Preset) -> Fed {
        Fed { surface_window: dnsr::Settings::preset(preset).uses_runs() && self.input == ShadowInput::HitMask, ..self }
    }
}

pub struct Row {
    pub pass: Pass,
    pub resource: String,
    pub fp32: f64,
    pub fp16: f64,
    pub access: Access,
    pub pixels: Pixels,
    pub when: When,
}

fn row(pass: Pass, resource: &str, fp32: f64, fp16: f64, access: Access, pixels: Pixels, when: When) -> Row {
    Row { pass, resource: resource.to_owned(), fp32, fp16, access, pixels, when }
}

use Access::*;
use Pass::*;
use Pixels::*;
use When::*;

/// The rows of the host's images in the formats fed (shadow input: a hit mask R32_UINT, or per-pixel visibility
/// R8_UNORM; output R16_SFLOAT).
fn host_rows(fed: Fed) -> Vec<Row> {
    let host = fed.host;
    let (depth, velocity, normals) = host.bytes();
    let depth_name = format!("depth (host, {:?})", host.depth());
    let velocity_name = format!("velocity (host, {:?})", host.velocity());
    let normals_name = format!("normals (host, {:?})", host.normals());
    let mut rows = match fed.input {
        // Classification reads a hit mask as it is (no prepare pass).
        ShadowInput::HitMask => vec![row(TileClassification, "hit mask (host, R32_UINT)", 4.0, 4.0, Read, Tiles, Always)],
        // A checkerboard input reads the traced half of each frame's mask: its words hold both halves.
        ShadowInput::Checkerboard => vec![row(Prepare, "hit mask (host, R32_UINT)", 4.0, 4.0, Read, Tiles, Always)],
        // Prepare derives the tile words from every pixel's visibility, classification its moments' window.
        ShadowInput::Visibility => vec![
            row(Prepare, "visibility (host, R8_UNORM)", 1.0, 1.0, Read, All, Always),
            row(TileClassification, "visibility (host, R8_UNORM)", 1.0, 1.0, Read, All, Always),
        ],
    };
    rows.extend([
        row(TileClassification, &depth_name, depth, depth, Read, All, Always),
        row(TileClassification, &velocity_name, velocity, velocity, Read, ActiveGroupReceivers, Always),
        row(TileClassification, &normals_name, normals, normals, Read, if fed.surface_window { ActiveGroups } else { Active }, Always),
        row(TileClassification, "output (host, R16_SFLOAT)", 2.0, 2.0, Write, ClearedGroups, Always),
        row(Filter, &depth_name, depth, depth, Read, All, FirstPass),
        row(Filter, &depth_name, depth, depth, Read, ClearedGroups, LaterPasses),
        // Every pixel's, cleared groups' too: pass 0 fetches them with the depth, before it knows, and writes them into
        // the depth copy.
        row(Filter, &normals_name, normals, normals, Read, All, FirstPass),
        row(Filter, "output (host, R16_SFLOAT)", 2.0, 2.0, Write, All, FinalPass),
    ]);
    rows
}

/// The rows of dnsr's internal images: the state table's accesses with this shadow input (no penumbra guidance, no
/// debug view), bytes per texel from their formats with that input.
fn internal_rows(input: ShadowInput) -> Vec<Row> {
    let applies = |c: Config| match c {
        Config::Any => true,
        Config::VisibilityInput => input != ShadowInput::HitMask,
        Config::CheckerboardInput => input == ShadowInput::Checkerboard,
        Config::PenumbraGuidance | Config::DebugView => false,
    };
    ACCESSES
        .iter()
        .filter(|a| applies(a.config))
        .map(|a| {
            let r = resource_of(a.target.image(0));
            let bytes = |p| format_bytes(r.format_for(p, input)) as f64;
            row(a.pass, &a.target.label_for(input), bytes(Precision::Fp32), bytes(Precision::Fp16), a.access, a.pixels, a.when)
        })
        .collect()
}

/// The bytes of one frame's passes with the host G-buffer in `host`'s formats. Per pass: the tile state it reads,
/// the host images it reads, the rest of its internal images (src/state/table.rs), the host image it writes.
pub fn model(fed: Fed) -> Vec<Row> {
    let (mut host, mut internal) = (host_rows(fed), internal_rows(fed.input));
    if fed.host_previous {
        // Classification's read of the depth copy becomes reads of the host's images over the same pixels.
        let depth_copy = dnsr::state_table::Target::Image(dnsr::state_table::Image::DepthCopy).label_for(fed.input);
        let is_copy_read = |r: &Row| r.pass == TileClassification && r.access == Read && r.resource == depth_copy;
        let copy_read = internal.iter().find(|r| is_copy_read(r)).expect("classification reads the depth copy");
        let (pixels, when) = (copy_read.pixels, copy_read.when);
        internal.retain(|r| !is_copy_read(r));
        let (depth, _, normals) = fed.host.bytes();
        host.push(row(TileClassification, &format!("previous depth (host, {:?})", fed.host.depth()), depth, depth, Read, pixels, when));
        if fed.surface_window {
            // The run features' turned-normal test reads the previous normal where it reads the moments.
            host.push(row(TileClassification, &format!("previous normals (host, {:?})", fed.host.normals()), normals, normals, Read, pixels, when));
        }
    }
    let tile_read = |r: &Row| r.pixels == Tiles && r.access == Read;
    let mut rows = Vec::new();
    for pass in [Prepare, TileClassification, Filter] {
        let of = |rows: &[Row], keep: &dyn Fn(&Row) -> bool| -> Vec<Row> {
            rows.iter()
                .filter(|r| r.pass == pass && keep(r))
                .map(|r| row(r.pass, &r.resource, r.fp32, r.fp16, r.access, r.pixels, r.when))
                .collect()
        };
        rows.extend(of(&internal, &tile_read));
        rows.extend(of(&host, &|r| r.access == Read));
        rows.extend(of(&internal, &|r| !tile_read(r)));
        rows.extend(of(&host, &|r| r.access == Write));
    }
    rows
}

/// Size of every pixel class in one frame (averaged over the frames measured).
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelCounts {
    pub all: f64,
    pub tiles: f64,
    pub receivers: f64,
    pub active: f64,
    pub history: f64,
    pub active_groups: f64,
    pub active_group_receivers: f64,
}

impl PixelCounts {
    pub fn get(&self, p: Pixels) -> f64 {
        match p {
            Tiles => self.tiles,
            All => self.all,
            Receivers => self.receivers,
            Active => self.active,
            History => self.history,
            ActiveGroups => self.active_groups,
            ActiveGroupReceivers => self.active_group_receivers,
            ClearedGroups => self.all - self.active_groups,
        }
    }

    /// Fractions of all pixels (tiles: count).
    pub fn to_json(self) -> Json {
        let f = |n: f64| Json::from(n / self.all.max(1.0));
        Json::obj([
            ("pixels", self.all.into()),
            ("tiles", self.tiles.into()),
            ("receivers", f(self.receivers)),
            ("active", f(self.active)),
            ("history", f(self.history)),
            ("active_groups", f(self.active_groups)),
            ("active_group_receivers", f(self.active_group_receivers)),
        ])
    }
}

/// One timed pass of a frame.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum PassId {
    Prepare,
    TileClassification,
    Filter(u32),
}

impl PassId {
    pub fn name(self) -> String {
        match self {
            PassId::Prepare => "prepare".into(),
            PassId::TileClassification => "tile classification".into(),
            PassId::Filter(k) => format!("filter {k}"),
        }
    }

    fn applies(self, r: &Row, filter_passes: u32) -> bool {
        match (self, r.pass) {
            (PassId::Prepare, Prepare) | (PassId::TileClassification, TileClassification) => true,
            (PassId::Filter(k), Filter) => r.when.applies(k, filter_passes),
            _ => false,
        }
    }
}

/// Whether filter pass `k` of `passes` skips groups whose two tiles are cleared (dnsr's src/passes/filter.rs:
/// pass 1, and a final pass after the first, write only what tile classification already wrote there).
fn skips_cleared(k: u32, passes: u32) -> bool {
    k == 1 || (k > 0 && k + 1 == passes)
}

/// (bytes read, bytes written) of one pass in a frame with these pixel counts.
pub fn pass_bytes(pass: PassId, filter_passes: u32, precision: Precision, counts: &PixelCounts, fed: Fed) -> (f64, f64) {
    let (mut read, mut write) = (0.0, 0.0);
    for r in model(fed).iter().filter(|r| pass.applies(r, filter_passes)) {
        let per = if precision == Precision::Fp16 { r.fp16 } else { r.fp32 };
        let pixels = match pass {
            PassId::Filter(k) if r.pixels == All && skips_cleared(k, filter_passes) => ActiveGroups,
            PassId::Filter(k) if r.pixels == ClearedGroups && skips_cleared(k, filter_passes) => continue,
            _ => r.pixels,
        };
        let bytes = per * counts.get(pixels);
        match r.access {
            Read => read += bytes,
            Write => write += bytes,
        }
    }
    (read, write)
}

pub fn pixels_doc(p: Pixels) -> &'static str {
    match p {
        Tiles => "per 8x4 tile",
        All => "every pixel",
        Receivers => "receivers (not sky)",
        Active => "receivers in tiles not cleared",
        History => "active receivers reusing history",
        ActiveGroups => "pixels of 8x8 groups with a tile not cleared",
        ActiveGroupReceivers => "receivers in 8x8 groups with a tile not cleared",
        ClearedGroups => "pixels of 8x8 groups whose two tiles are cleared",
    }
}

fn when_doc(w: When) -> &'static str {
    match w {
        Always => "every pass",
        WritesIntermediate => "every pass but the last",
        FinalPass => "last pass",
        FirstPass => "pass 0",
        LaterPasses => "every pass after the first",
    }
}

fn pass_doc(p: Pass) -> &'static str {
    match p {
        Prepare => "prepare",
        TileClassification => "tile classification",
        Filter => "filter",
    }
}

pub fn model_json(fed: Fed) -> Json {
    Json::Arr(
        model(fed)
            .iter()
            .map(|r| {
                Json::obj([
                    ("pass", pass_doc(r.pass).into()),
                    ("resource", r.resource.as_str().into()),
                    ("bytes_fp32", r.fp32.into()),
                    ("bytes_fp16", r.fp16.into()),
                    ("access", (if r.access == Read { "read" } else { "write" }).into()),
                    ("pixels", format!("{:?}", r.pixels).into()),
                    ("pixels_meaning", pixels_doc(r.pixels).into()),
                    ("filter_passes", (if r.pass == Filter { when_doc(r.when) } else { "-" }).into()),
                ])
            })
            .collect(),
    )
}

/// The table as Markdown.
pub fn model_markdown(fed: Fed) -> String {
    let mut s = String::from("| pass | resource | B fp32 | B fp16 | access | per | filter passes |\n|---|---|---|---|---|---|---|\n");
    for r in model(fed) {
        s += &format!(
            "| {} | {} | {} | {} | {} | {} | {} |\n",
            pass_doc(r.pass),
            r.resource,
            r.fp32,
            r.fp16,
            if r.access == Read { "read" } else { "write" },
            pixels_doc(r.pixels),
            if r.pass == Filter { when_doc(r.when) } else { "" }
        );
    }
    s
}
