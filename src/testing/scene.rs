//! Truth-known synthetic input: a camera looking down at a ground plane (with sky beyond its edge), a
//! visibility field v(x, z) on the plane, and a 1-spp hit mask drawn as Bernoulli(v).

use glam::{DMat4, DVec3, DVec4, Mat4, Vec3};

/// Camera above the plane y = 0, looking straight down; world -z maps towards NDC -y, the top of the image.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    /// Position in world space.
    pub eye: DVec3,
    /// Vertical field of view in radians.
    pub fov_y: f64,
    /// Near plane distance.
    pub near: f64,
    /// Far plane distance (ignored when `infinite_far`).
    pub far: f64,
    /// Reverse-Z depth.
    pub inverted: bool,
    /// Infinite far plane.
    pub infinite_far: bool,
    /// Orthographic projection of this vertical extent in world units (None: perspective).
    pub orthographic: Option<f64>,
}

impl Camera {
    /// A camera `height` units above (x, z).
    pub fn above(x: f64, z: f64, height: f64) -> Camera {
        Camera { eye: DVec3::new(x, height, z), fov_y: 0.9, near: 0.1, far: 100.0, inverted: false, infinite_far: false, orthographic: None }
    }

    fn projection(&self, aspect: f64) -> DMat4 {
        // Right-handed view space (camera looks down -z), clip depth in [0, 1].
        if let Some(height) = self.orthographic {
            let (n, far) = (self.near, self.far);
            let (near_z, far_z) = if self.inverted { (1.0, 0.0) } else { (0.0, 1.0) };
            // z_clip = a * z + b with z = -n -> near_z and z = -far -> far_z; w = 1.
            let a = (near_z - far_z) / (far - n);
            let b = near_z + a * n;
            return DMat4::from_cols(
                DVec4::new(2.0 / (height * aspect), 0.0, 0.0, 0.0),
                DVec4::new(0.0, 2.0 / height, 0.0, 0.0),
                DVec4::new(0.0, 0.0, a, 0.0),
                DVec4::new(0.0, 0.0, b, 1.0),
            );
        }
        let f = 1.0 / (self.fov_y * 0.5).tan();
        let (n, far) = (self.near, self.far);
        // z_clip = a * z + b, w_clip = -z.
        let (a, b) = match (self.inverted, self.infinite_far) {
            (false, false) => (far / (n - far), far * n / (n - far)),
            (true, false) => (n / (far - n), far * n / (far - n)),
            (false, true) => (-1.0, -n),
            (true, true) => (0.0, n),
        };
        DMat4::from_cols(
            DVec4::new(f / aspect, 0.0, 0.0, 0.0),
            DVec4::new(0.0, f, 0.0, 0.0),
            DVec4::new(0.0, 0.0, a, -1.0),
            DVec4::new(0.0, 0.0, b, 0.0),
        )
    }

    /// View matrix, camera-relative when `origin` is the camera position (large-coordinate scenes).
    fn view(&self, origin: DVec3) -> DMat4 {
        let eye = self.eye - origin;
        // Looking straight down -y with -z as screen-up.
        let (fwd, up) = (DVec3::NEG_Y, DVec3::NEG_Z);
        let s = fwd.cross(up).normalize();
        let u = s.cross(fwd);
        DMat4::from_cols(
            DVec4::new(s.x, u.x, -fwd.x, 0.0),
            DVec4::new(s.y, u.y, -fwd.y, 0.0),
            DVec4::new(s.z, u.z, -fwd.z, 0.0),
            DVec4::new(-s.dot(eye), -u.dot(eye), fwd.dot(eye), 1.0),
        )
    }
}

/// Visibility field on the plane: world (x, z) -> fraction of the light visible, in [0, 1].
pub type Visibility<'a> = &'a dyn Fn(f64, f64) -> f64;

/// One frame of G-buffer, mask and truth, plus the matrices dnsr needs.
#[derive(Clone)]
pub struct FrameInputs {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Depth per pixel (R32_SFLOAT), 1 (or 0 inverted) for sky.
    pub depth: Vec<f32>,
    /// World normal per pixel (RGBA32F, w unused).
    pub normals: Vec<[f32; 4]>,
    /// uv offset to the previous frame's position per pixel.
    pub velocity: Vec<[f32; 2]>,
    /// Hit mask, FidelityFX convention (bit = 1 occluded), ceil(W/8) x ceil(H/4).
    pub mask: Vec<u32>,
    /// Distance to the occluder where the mask says the ray hit (0 elsewhere): the penumbra guidance input.
    pub hit_distance: Vec<f32>,
    /// Per-pixel visibility for a visibility input (`ShadowInput::Visibility`): the mask's ray as 0 or 1, or the
    /// mean of k rays after `trace_rays`.
    pub visibility: Vec<f32>,
    /// True visibility per pixel (1 for sky).
    pub truth: Vec<f32>,
    /// Receiver (plane) pixels.
    pub receiver: Vec<bool>,
    /// Current clip -> view.
    pub projection_inverse: Mat4,
    /// Current clip -> previous clip.
    pub reprojection: Mat4,
    /// Current clip -> world (camera-relative world when `relative` was used).
    pub view_projection_inverse: Mat4,
    /// Eye in the same space as `view_projection_inverse`.
    pub eye: Vec3,
}

impl FrameInputs {
    /// A frame with every pixel sky at `sky_depth`, normals up, no motion, an empty mask and truth 1, for the
    /// given (f64) matrices: clip -> view, current and previous world -> clip; `eye` in the same world space.
    pub fn blank(width: u32, height: u32, sky_depth: f32, proj: DMat4, vp: DMat4, vp_prev: DMat4, eye: Vec3) -> FrameInputs {
        let n = (width * height) as usize;
        let vp_inv = vp.inverse();
        FrameInputs {
            width,
            height,
            depth: vec![sky_depth; n],
            normals: vec![[0.0, 1.0, 0.0, 0.0]; n],
            velocity: vec![[0.0; 2]; n],
            hit_distance: vec![0.0; n],
            visibility: vec![1.0; n],
            mask: vec![0; (width.div_ceil(8) * height.div_ceil(4)) as usize],
            truth: vec![1.0; n],
            receiver: vec![false; n],
            projection_inverse: proj.inverse().as_mat4(),
            reprojection: (vp_prev * vp_inv).as_mat4(),
            view_projection_inverse: vp_inv.as_mat4(),
            eye,
        }
    }
}

/// A deterministic per-pixel random number in [0, 1).
pub fn hash01(seed: u64, x: u32, y: u32) -> f64 {
    let mut z = seed ^ ((x as u64) << 32 | y as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// Builds one frame. The plane covers world |x| < `plane_half_width` (beyond it: sky). `seed` draws the mask;
/// `prev` is the previous frame's camera.
pub fn render(
    width: u32,
    height: u32,
    cam: &Camera,
    prev: &Camera,
    plane_half_width: f64,
    visibility: Visibility,
    seed: u64,
) -> FrameInputs {
    render_with_blockers(width, height, cam, prev, plane_half_width, visibility, &|_, _| 0.0, seed)
}

/// `render`, with the distance to the occluder at world (x, z) written where a ray hit (`FrameInputs::hit_distance`).
#[allow(clippy::too_many_arguments)]
pub fn render_with_blockers(
    width: u32,
    height: u32,
    cam: &Camera,
    prev: &Camera,
    plane_half_width: f64,
    visibility: Visibility,
    blocker: &dyn Fn(f64, f64) -> f64,
    seed: u64,
) -> FrameInputs {
    let ground = Ground { half_width: plane_half_width, visibility, blocker };
    render_scene(width, height, cam, prev, &ground, &[], seed)
}

/// The ground plane y = 0 of a scene: where it ends (sky beyond |x| = `half_width`), its visibility field and the
/// distance to the occluder a ray that hits it finds.
pub struct Ground<'a> {
    /// The plane covers world |x| < this.
    pub half_width: f64,
    /// Visibility at world (x, z).
    pub visibility: Visibility<'a>,
    /// Occluder distance at world (x, z), written where a ray hit.
    pub blocker: &'a dyn Fn(f64, f64) -> f64,
}

/// A two-sided parallelogram above the ground (a box face, one face of a thin shell): the points
/// `corner + s * edges[0] + t * edges[1]` for s and t in [0, 1]. It hides what lies behind it, so a moving camera
/// uncovers the ground beside it (disocclusion), and a camera that crosses its plane sees its other side (a shell
/// that flips). Static: its motion vectors are the camera's.
pub struct Quad<'a> {
    /// One corner, world units.
    pub corner: DVec3,
    /// The two edges from `corner`; `edges[0] x edges[1]` is the front side's normal.
    pub edges: [DVec3; 2],
    /// Visibility of the front and back side at (s, t).
    pub sides: [Visibility<'a>; 2],
}

impl Quad<'_> {
    /// The ray parameter, world normal of the side facing the ray, and the visibility there, where the ray
    /// `from + k * dir` (k > 0) hits this quad.
    fn hit(&self, from: DVec3, dir: DVec3) -> Option<(f64, DVec3, f64)> {
        let [e0, e1] = self.edges;
        let n = e0.cross(e1);
        let facing = n.dot(dir);
        if facing.abs() < 1e-12 {
            return None;
        }
        let k = n.dot(self.corner - from) / facing;
        let d = from + dir * k - self.corner;
        let (a, b, c) = (e0.length_squared(), e0.dot(e1), e1.length_squared());
        let det = a * c - b * b;
        let s = (d.dot(e0) * c - d.dot(e1) * b) / det;
        let t = (d.dot(e1) * a - d.dot(e0) * b) / det;
        if !(k > 0.0 && (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t)) {
            return None;
        }
        let front = facing < 0.0;
        let normal = if front { n.normalize() } else { -n.normalize() };
        Some((k, normal, self.sides[if front { 0 } else { 1 }](s, t)))
    }
}

/// Builds one frame of the ground and the quads above it. `seed` draws the mask; `prev` is the previous frame's
/// camera.
pub fn render_scene(width: u32, height: u32, cam: &Camera, prev: &Camera, ground: &Ground, quads: &[Quad], seed: u64) -> FrameInputs {
    let aspect = width as f64 / height as f64;
    // Camera-relative matrices: both frames relative to the current eye, so large world coordinates cancel in f64.
    let origin = cam.eye;
    let proj = cam.projection(aspect);
    let vp = proj * cam.view(origin);
    let vp_prev = prev.projection(aspect) * prev.view(origin);
    let vp_inv = vp.inverse();
    let sky_depth = if cam.inverted { 0.0 } else { 1.0 };
    let mut f = FrameInputs::blank(width, height, sky_depth, proj, vp, vp_prev, (cam.eye - origin).as_vec3());
    for y in 0..height {
        for x in 0..width {
            let i = (y * width + x) as usize;
            let uv = [(x as f64 + 0.5) / width as f64, (y as f64 + 0.5) / height as f64];
            let ndc = [uv[0] * 2.0 - 1.0, uv[1] * 2.0 - 1.0];
            let unproject = |z: f64| {
                let p = vp_inv * DVec4::new(ndc[0], ndc[1], z, 1.0);
                p.truncate() / p.w
            };
            let a = unproject(if cam.inverted { 1.0 } else { 0.0 });
            let dir = unproject(0.5) - a;
            // The nearest surface: (ray parameter, normal, visibility, occluder distance).
            let t = -(a.y + origin.y) / dir.y;
            let world = a + dir * t + origin;
            let mut nearest = (t > 0.0 && world.x.abs() < ground.half_width)
                .then(|| (t, DVec3::Y, (ground.visibility)(world.x, world.z), (ground.blocker)(world.x, world.z)));
            for q in quads {
                let hit = q.hit(a + origin, dir);
                if let Some((k, normal, v)) = hit.filter(|h| nearest.is_none_or(|n| h.0 < n.0)) {
                    nearest = Some((k, normal, v, 0.0));
                }
            }
            let mut lit = true;
            if let Some((k, normal, v, blocker)) = nearest {
                let hit = a + dir * k;
                let clip = vp * DVec4::new(hit.x, hit.y, hit.z, 1.0);
                f.depth[i] = (clip.z / clip.w) as f32;
                let prev_clip = vp_prev * DVec4::new(hit.x, hit.y, hit.z, 1.0);
                let prev_uv = [prev_clip.x / prev_clip.w * 0.5 + 0.5, prev_clip.y / prev_clip.w * 0.5 + 0.5];
                f.velocity[i] = [(prev_uv[0] - uv[0]) as f32, (prev_uv[1] - uv[1]) as f32];
                f.normals[i] = [normal.x as f32, normal.y as f32, normal.z as f32, 0.0];
                let v = v.clamp(0.0, 1.0);
                f.truth[i] = v as f32;
                f.receiver[i] = true;
                lit = hash01(seed, x, y) < v;
                if !lit {
                    f.hit_distance[i] = blocker as f32;
                }
            }
            if !lit {
                f.set_hit(x, y);
            }
            f.visibility[i] = lit as u32 as f32;
        }
    }
    f
}

impl FrameInputs {
    /// The hit mask's word and bit of pixel (x, y) (8x4 tiles, bit (y % 4) * 8 + x % 8).
    fn mask_bit(&self, x: u32, y: u32) -> (usize, u32) {
        (((y / 4) * self.width.div_ceil(8) + x / 8) as usize, 1 << ((y % 4) * 8 + (x % 8)))
    }

    /// Whether pixel (x, y)'s ray hit (its mask bit is set).
    pub fn hit(&self, x: u32, y: u32) -> bool {
        let (word, bit) = self.mask_bit(x, y);
        self.mask[word] & bit != 0
    }

    /// Marks pixel (x, y)'s ray as hit.
    pub fn set_hit(&mut self, x: u32, y: u32) {
        let (word, bit) = self.mask_bit(x, y);
        self.mask[word] |= bit;
    }

    /// Makes `visibility` the mean of `rays` shadow rays per receiver: the mask's ray (drawn with `seed`, so one
    /// ray equals the mask) and `rays - 1` more, each hitting with probability 1 - truth.
    pub fn trace_rays(&mut self, rays: u32, seed: u64) {
        for y in 0..self.height {
            for x in 0..self.width {
                let i = (y * self.width + x) as usize;
                if !self.receiver[i] {
                    continue;
                }
                let first = !self.hit(x, y);
                let more = (1..rays).filter(|&r| hash01(seed ^ (r as u64).wrapping_mul(0xA24B_AED4_963E_E407), x, y) < self.truth[i] as f64);
                self.visibility[i] = (first as u32 + more.count() as u32) as f32 / rays as f32;
            }
        }
    }
}
