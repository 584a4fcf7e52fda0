//! GPU shaders of sky-core's sky models: a self-contained `sky_radiance(dir)` per model, in
//! GLSL ES 3.00 (WebGL2) and WGSL (WebGPU), printed from one description of its functions
//! ([`ir`], [`mod@print`]), with the values of one sky packed by sky-core on the CPU as the
//! shader's parameters.
//!
//! Everything that depends only on the sun and the atmosphere is computed once by sky-core's
//! constructors (Preetham's Perez coefficients, the neural network with √t, θ_sun, eq. 10's
//! rotation and the input scaling folded into its first layer, AOAS's ray constants, SH
//! coefficients, the daylight sky's one or two networks folded likewise with their blend
//! weights and the diffuse illuminance of its tables) and passed as an array of `vec4`s named
//! `sky_<model>`; the shader text holds only the per-direction part, so one compiled program
//! draws every sky of its model (the daylight sky's: every sun from the zenith to 18° below the
//! horizon and every aerosol optical depth).
//!
//! ```
//! use sky_gpu::{Language, Model, Storage};
//! use sky_core::{PreethamSky, Sun};
//!
//! let glsl = Model::Preetham.shader().source(Language::Glsl, Storage::UNIFORM);
//! assert!(glsl.contains("uniform vec4 sky_preetham[7];"));
//! assert!(glsl.contains("vec3 sky_radiance(vec3 dir)"));
//! let sky = PreethamSky::new(Sun::new(0.6, 1.0)?, 3.0)?;
//! let params = sky_gpu::models::preetham::params(&sky); // the uniform's 7 × 4 floats
//! assert_eq!(params.len(), 28);
//! # Ok::<(), sky_core::SkyError>(())
//! ```
//!
//! **Axes and units** are sky-core's: directions in its frame (+z up, any length); linear
//! sRGB in cd/m² for the Preetham, neural (shipped weights), SH and daylight skies, O'Neil's relative
//! units for AOAS. **Accuracy**: the same operations as sky-core in the same order, with the
//! GPU's exp2, atan2, sqrt and inverseSqrt for sky-core's polynomial kernels; the browser tests
//! hold each shader to sky-core's CPU values within 1e-3 relative (sky-wasm, `scripts/wasm.sh
//! test`), and naga parses and validates every generated shader (`tests/naga.rs`).

pub mod ir;
pub mod models;
pub mod print;

use core::fmt;

pub use print::Language;

use ir::{Expr, Function};
use print::{Printer, float_literal};

/// A sky model with a shader.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Model {
    /// The Preetham sky (Perez distribution, seed 002).
    Preetham,
    /// The neural sky of seed 000 with 12 hidden neurons (any weight file of that shape).
    Neural,
    /// The AOAS sky (seed 004), styles without patterns or ambiguity.
    Aoas,
    /// The spherical-harmonics sky (seed 001), up to seven bands.
    Sh,
    /// sky-core's physical daylight sky (`DaylightSky`: day, dusk and night networks, the sun
    /// from the zenith to 18° below the horizon).
    Daylight,
}

impl Model {
    /// Every model.
    pub const ALL: [Self; 5] = [
        Self::Preetham,
        Self::Neural,
        Self::Aoas,
        Self::Sh,
        Self::Daylight,
    ];

    /// The model's name, as the command line spells it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Preetham => "preetham",
            Self::Neural => "neural",
            Self::Aoas => "aoas",
            Self::Sh => "sh",
            Self::Daylight => "daylight",
        }
    }

    /// The name of the shader's parameter array, `sky_<model>`.
    #[must_use]
    pub fn params_name(self) -> &'static str {
        match self {
            Self::Preetham => "sky_preetham",
            Self::Neural => "sky_neural",
            Self::Aoas => "sky_aoas",
            Self::Sh => "sky_sh",
            Self::Daylight => "sky_daylight",
        }
    }

    /// The model's shader.
    #[must_use]
    pub fn shader(self) -> Shader {
        match self {
            Self::Preetham => models::preetham::shader(),
            Self::Neural => models::neural::shader(12),
            Self::Aoas => models::aoas::shader(),
            Self::Sh => models::sh::shader(),
            Self::Daylight => models::daylight::shader(),
        }
    }
}

impl fmt::Display for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Element `i` of `model`'s parameter array.
pub(crate) fn param(model: Model, i: i32) -> Expr {
    ir::name(model.params_name()).at(ir::int(i))
}

/// A sky that has no shader (the message says why).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UnsupportedSky(pub &'static str);

impl fmt::Display for UnsupportedSky {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)
    }
}

impl std::error::Error for UnsupportedSky {}

/// Where a shader's parameters live.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Storage<'a> {
    /// A uniform array, set per sky by the application: in GLSL a plain `uniform vec4
    /// sky_<model>[N]`, in WGSL `var<uniform>` at the given group and binding.
    Uniform {
        /// WGSL `@group`.
        group: u32,
        /// WGSL `@binding`.
        binding: u32,
    },
    /// The parameters of one sky as constants in the text (4 × N floats, as packed by the
    /// model's `params`): a shader for that sky alone.
    Constant(&'a [f32]),
}

impl Storage<'_> {
    /// A uniform array at WGSL group 0, binding 0.
    pub const UNIFORM: Storage<'static> = Storage::Uniform {
        group: 0,
        binding: 0,
    };
}

/// One model's shader: its functions, the last of which is `sky_radiance(dir) -> vec3`.
#[derive(Debug, Clone, PartialEq)]
pub struct Shader {
    /// The model.
    pub model: Model,
    /// The parameter array's length in `vec4`s.
    pub params_len: usize,
    /// What the shader computes, in which units, and the parameters' layout.
    pub doc: String,
    /// The functions, each before its callers.
    pub functions: Vec<Function>,
}

impl Shader {
    /// The complete shader text: a header comment, the parameters' declaration and the
    /// functions. A [`Storage::Constant`] of the wrong length is padded with zeros or cut to
    /// the shader's parameter count (the model's `params` functions give the exact length).
    #[must_use]
    pub fn source(&self, lang: Language, storage: Storage<'_>) -> String {
        let mut p = Printer::new(lang);
        let (flag, one_sky) = match storage {
            Storage::Uniform { .. } => ("", ""),
            Storage::Constant(_) => (
                " --constants",
                "\nThe parameters are those of one sky, as constants.",
            ),
        };
        p.comment(&format!(
            "generated by sky-gpu from sky-core's {} model (`sky-train export --format {} --model {}{flag}`), do not edit\n\n{}{one_sky}",
            self.model,
            lang.extension(),
            self.model,
            self.doc
        ));
        let mut text = p.out;
        text.push_str(&self.declaration(lang, storage));
        text.push('\n');
        text.push_str(&self.functions_source(lang));
        text
    }

    /// The parameters' declaration alone (one statement).
    #[must_use]
    pub fn declaration(&self, lang: Language, storage: Storage<'_>) -> String {
        let (name, n) = (self.model.params_name(), self.params_len);
        match (lang, storage) {
            (Language::Glsl, Storage::Uniform { .. }) => format!("uniform vec4 {name}[{n}];\n"),
            (Language::Wgsl, Storage::Uniform { group, binding }) => format!(
                "@group({group}) @binding({binding}) var<uniform> {name}: array<vec4<f32>, {n}>;\n"
            ),
            (lang, Storage::Constant(values)) => {
                let vec4 = lang.ty(ir::Ty::Vec4);
                let rows: Vec<String> = (0..n)
                    .map(|i| {
                        let c: Vec<String> = (0..4)
                            .map(|k| float_literal(values.get(4 * i + k).copied().unwrap_or(0.0)))
                            .collect();
                        format!("    {vec4}({})", c.join(", "))
                    })
                    .collect();
                let rows = rows.join(",\n");
                match lang {
                    Language::Glsl => {
                        format!("const vec4 {name}[{n}] = vec4[{n}](\n{rows}\n);\n")
                    }
                    Language::Wgsl => format!(
                        "var<private> {name}: array<vec4<f32>, {n}> = array<vec4<f32>, {n}>(\n{rows}\n);\n"
                    ),
                }
            }
        }
    }

    /// The functions alone, without the parameters' declaration.
    #[must_use]
    pub fn functions_source(&self, lang: Language) -> String {
        let mut p = Printer::new(lang);
        for (i, f) in self.functions.iter().enumerate() {
            if i > 0 {
                p.out.push('\n');
            }
            p.function(f);
        }
        p.out
    }
}

/// The JavaScript module of every model's shader text (sky-wasm's `shaders.js`): per model an
/// export `{ glsl, wgsl, params }` (the uniform texts, WGSL at group 0, binding 0, and the
/// parameter array's length in vec4s).
#[must_use]
pub fn js_module() -> String {
    let mut out = String::from(
        "// generated by sky-gpu (`sky-train export --format js`), do not edit\n\
         //\n\
         // Each sky model's shader, `sky_radiance(dir)` in GLSL ES 3.00 and WGSL (WGSL parameters\n\
         // at @group(0) @binding(0)), and the length of its parameter array in vec4s; a sky's\n\
         // parameters come from sky-wasm's `Sky.shaderParams()`.\n",
    );
    for model in Model::ALL {
        let shader = model.shader();
        let text = |lang| js_string(&shader.source(lang, Storage::UNIFORM));
        out.push_str(&format!(
            "\n/** The {model} sky's shader. */\nexport const {model} = {{\n  params: {},\n  glsl: {},\n  wgsl: {},\n}};\n",
            shader.params_len,
            text(Language::Glsl),
            text(Language::Wgsl),
        ));
    }
    out
}

/// `s` as a JavaScript string literal.
fn js_string(s: &str) -> String {
    let mut out = String::from('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
