//! Rust blocks with a GLSL twin of the same layout: the constant blocks the host writes and the passes read are
//! declared once, with `gpu_block!`, wherever the pass they belong to is described (constants.rs, passes/), and
//! constants.rs writes every twin into the generated GLSL header.
//!
//! Every member is a 16-byte vector or a matrix, which makes `#[repr(C)]` and std140 agree without padding rules
//! to remember.

/// A Rust type with a GLSL spelling of identical std140 / `repr(C)` layout.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) trait GlslType {
    const GLSL: &'static str;
}
impl GlslType for [f32; 4] {
    const GLSL: &'static str = "vec4";
}
impl GlslType for [u32; 4] {
    const GLSL: &'static str = "uvec4";
}
impl GlslType for [[f32; 4]; 4] {
    const GLSL: &'static str = "mat4";
}

/// Declares a `#[repr(C)]` Pod struct and the GLSL struct of the same layout.
macro_rules! gpu_block {
    ($(#[$m:meta])* pub(crate) struct $name:ident as $glsl:literal {
        $( $(#[$fm:meta])* $f:ident : $t:ty ),* $(,)?
    }) => {
        $(#[$m])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
        pub(crate) struct $name { $( $(#[$fm])* pub $f: $t ),* }
        #[cfg_attr(not(test), allow(dead_code))]
        impl $name {
            /// The GLSL declaration of this block's struct.
            pub(crate) fn glsl() -> String {
                use std::fmt::Write as _;
                let mut s = format!("struct {} {{\n", $glsl);
                $( let _ = writeln!(s, "    {} {};", <$t as $crate::glsl::GlslType>::GLSL, stringify!($f)); )*
                s.push_str("};\n");
                s
            }
        }
    };
}
pub(crate) use gpu_block;
