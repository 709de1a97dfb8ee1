//! The deformation methods and their settings: the list of methods (`methods!`, one line
//! each), the [`Method`] and [`MethodOptions`] enums made from it, and each method's options
//! with their ranges and their settings by name ([`Settings`], which every reader of
//! options goes through). Plain data: nothing here knows a deformer, so every file of
//! `deform` can use it.

use std::fmt;
use std::ops::RangeInclusive;

/// The list of methods, one line each: `Variant("name", Options)`, after the documentation
/// of the [`Method`] variant. `methods!(callback)` hands the list to `callback!`, which
/// writes whatever needs a case per method: the enums below,
/// the enum of solvers and [`MethodOptions::orders`]' dispatch in `method.rs` (through the
/// `Build` trait each options type implements beside its solver) and the settings by name in
/// `settings.rs` (through [`Settings`], implemented beside each options type here).
macro_rules! methods {
    ($callback:ident) => {
        $callback! {
            /// As-Killing-As-Possible vector fields (the paper).
            Akap("akap", AkapOptions),
            /// As-rigid-as-possible local/global iterations.
            Arap("arap", ArapOptions),
            /// Moving least squares (Schaefer et al. 2006): rigid, similarity or affine.
            Mls("mls", MlsOptions),
            /// Point-to-point Cauchy-Green coordinates (Weber et al. 2009): a conformal map
            /// from a cage.
            CauchyGreen("cauchy-green", CauchyGreenOptions),
        }
    };
}
pub(crate) use methods;

/// Writes [`Method`], [`MethodOptions`] and their cases from the list.
macro_rules! method_enums {
    ($($(#[$doc:meta])* $variant:ident($name:literal, $options:ident),)*) => {
        /// The deformation methods.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum Method {
            $($(#[$doc])* $variant,)*
        }

        impl Method {
            /// The name the JavaScript API and sessions use: `"akap"`, `"arap"`, `"mls"` or
            /// `"cauchy-green"`.
            pub fn name(self) -> &'static str {
                match self {
                    $(Self::$variant => $name,)*
                }
            }
        }

        /// A method with its settings.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum MethodOptions {
            $(#[doc = concat!("`", $name, "` with these options.")] $variant($options),)*
        }

        impl MethodOptions {
            /// Which method.
            pub fn method(&self) -> Method {
                match self {
                    $(Self::$variant(_) => Method::$variant,)*
                }
            }
        }
    };
}

methods!(method_enums);

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Default for MethodOptions {
    fn default() -> Self {
        Self::Akap(AkapOptions::default())
    }
}

/// How one setting reads and writes a method's options `O`.
pub enum Access<O: 'static> {
    /// A number: getter and setter.
    Number(fn(&O) -> f64, fn(&mut O, f64)),
    /// A whole number: getter and setter.
    Whole(fn(&O) -> usize, fn(&mut O, usize)),
    /// `true` or `false`: getter and setter.
    Bool(fn(&O) -> bool, fn(&mut O, bool)),
    /// One of the words: getter and setter of the word's index.
    Word(&'static [&'static str], fn(&O) -> usize, fn(&mut O, usize)),
}

/// One setting of a method: its name (as the JavaScript API and sessions spell it) and how
/// to read and write it.
pub struct Setting<O: 'static> {
    /// The name, e.g. `"lambda"`.
    pub name: &'static str,
    /// Reading and writing it.
    pub access: Access<O>,
}

/// A method's options type, with its settings by name. Ranges beyond a setting's kind (a
/// number's bounds, say) are the method's `check`, run after the settings are set.
pub trait Settings: Sized + 'static {
    /// Every setting a caller may name, in the order they are written.
    const SETTINGS: &'static [Setting<Self>];
}

/// How AKAP's vertices follow the velocity field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Integrator {
    /// Along logarithmic spirals (the paper's method, eqs. (14)-(16); reproduces rigid
    /// motions exactly).
    #[default]
    Spiral,
    /// Straight along the velocity, `p <- p + U` (the paper's ablation; dilates rotations).
    Linear,
}

/// The values [`AkapOptions::lambda`] may take: 1e-6 to 1e10.
///
/// lambda weighs the handle penalties (eq. (3)) against the Killing energy, whose matrix
/// entries are dimensionless: a few units per vertex (about 1 to 10; up to 1e6 on slivers,
/// see [`super::akap::killing::SLIVER_LIMIT`]) whatever the mesh's size, scale or
/// resolution, since the energy of a triangle is its area times squared gradients. So the
/// range is absolute. Both ends are where rounding starts to show, measured on the
/// gingerbread figure (786 to 32,447 vertices, two handles, one step compared with the steps
/// at ten times and a tenth the lambda):
/// - below, the penalty drowns in the rounding of K (1e-16 of its entries, summed over the
///   vertices): the rigid motions, which cost no energy, are pinned by lambda alone. At 1e-8
///   the field carries noise of 2e-5 (786 vertices) to 5e-4 (32k) of its size, at 1e-6 of
///   1e-6 to 5e-6, and near 1e-14 the factorisation fails;
/// - above, step 2's right-hand side, `lambda (u - W U0)`, is a difference of nearly equal
///   velocities times lambda: relative noise of about 2e-18 lambda (2e-8 at 1e10, 6e-7 at
///   1e12, 1e-2 at 1e16), and at 1e308 the penalties overflow.
pub const LAMBDA_RANGE: RangeInclusive<f64> = 1e-6..=1e10;

/// The values a triangle's stiffness may take ([`super::Deformer::set_stiffness`]): 1e-3 to
/// 1e3, a million from the softest to the stiffest, so that the Killing matrix's entries
/// stay within the range `LAMBDA_RANGE` was measured for.
pub const STIFFNESS_RANGE: RangeInclusive<f64> = 1e-3..=1e3;

/// AKAP's settings ([`super::AkapSolver`], behind a [`super::Deformer`]), with builders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AkapOptions {
    /// Weight of the soft handle constraints of step 1, in [`LAMBDA_RANGE`] (1e-6 to 1e10;
    /// default 100).
    pub lambda: f64,
    /// Whether step 2 (the Dirichlet re-solve, eq. (4)) runs.
    pub dirichlet: bool,
    /// How vertices move.
    pub integrator: Integrator,
}

/// AKAP's settings under their old name, from when `Deformer` meant AKAP.
#[deprecated(note = "AKAP's options are `AkapOptions`; `Deformer` is now any method's deformer")]
pub type DeformerOptions = AkapOptions;

impl Default for AkapOptions {
    fn default() -> Self {
        Self { lambda: 100.0, dirichlet: true, integrator: Integrator::Spiral }
    }
}

impl Settings for AkapOptions {
    const SETTINGS: &'static [Setting<Self>] = &[
        Setting { name: "lambda", access: Access::Number(|o| o.lambda, |o, x| o.lambda = x) },
        Setting { name: "dirichlet", access: Access::Bool(|o| o.dirichlet, |o, b| o.dirichlet = b) },
        Setting {
            name: "integrator",
            access: Access::Word(
                &["spiral", "linear"],
                |o| o.integrator as usize,
                |o, i| o.integrator = [Integrator::Spiral, Integrator::Linear][i],
            ),
        },
    ];
}

impl AkapOptions {
    /// Sets lambda.
    pub fn with_lambda(mut self, lambda: f64) -> Self {
        self.lambda = lambda;
        self
    }
    /// Switches the Dirichlet step on or off.
    pub fn with_dirichlet(mut self, on: bool) -> Self {
        self.dirichlet = on;
        self
    }
    /// Sets the integrator.
    pub fn with_integrator(mut self, integrator: Integrator) -> Self {
        self.integrator = integrator;
        self
    }
}

/// The most local/global iterations an ARAP step may run at a fixed count (`tolerance` 0),
/// the `iterations` option's maximum in Rust and JavaScript alike, so that one step's work
/// stays bounded: each iteration costs about a solve (0.12 ms natively at 1,089
/// vertices, growing like n log n), so 1000 of them take about 0.12 s there. That is far
/// more than a frame needs: iterations converge linearly, each step starts from the last
/// pose, and the widget runs 10. Convergence runs ([`ArapOptions::until_converged`],
/// [`super::Deformer::iterate`]) stop when converged and take a larger count.
pub const MAX_ITERATIONS: usize = 1000;

/// The most iterations an ARAP convergence run (a `tolerance` above 0:
/// [`ArapOptions::until_converged`], [`super::Deformer::iterate`]) may be allowed: it
/// stops when converged, but a tolerance finer than rounding never is, and a step must end.
pub const MAX_CONVERGENCE_ITERATIONS: usize = 1_000_000;

/// ARAP's settings ([`super::ArapSolver`]), with builders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArapOptions {
    /// Local/global iterations per step (at most): from 1 to [`MAX_ITERATIONS`] when
    /// `tolerance` is 0, to [`MAX_CONVERGENCE_ITERATIONS`] with a tolerance.
    pub iterations: usize,
    /// A step stops early once an iteration moves no vertex further than `tolerance`
    /// times the rest shape's bounding-box diagonal (0: always run `iterations`), from 0
    /// to 1 (a move as large as the shape is no convergence). With a tolerance,
    /// `iterations` only bounds a step and may exceed [`MAX_ITERATIONS`] (for converged
    /// poses in tests and `lab/compare`).
    pub tolerance: f64,
}

impl Default for ArapOptions {
    fn default() -> Self {
        Self { iterations: 10, tolerance: 0.0 }
    }
}

impl Settings for ArapOptions {
    /// `tolerance` (convergence runs, for tests and `lab/compare`) is not a setting:
    /// the JavaScript API and sessions run a fixed count, up to [`MAX_ITERATIONS`].
    const SETTINGS: &'static [Setting<Self>] =
        &[Setting { name: "iterations", access: Access::Whole(|o| o.iterations, |o, n| o.iterations = n) }];
}

impl ArapOptions {
    /// Sets the number of iterations per step (1 to [`MAX_ITERATIONS`]).
    pub fn with_iterations(mut self, iterations: usize) -> Self {
        self.iterations = iterations;
        self
    }

    /// Iterates until an iteration moves no vertex further than `tolerance` times the
    /// shape's size, or `max_iterations` have run (for tests and final poses; with a
    /// tolerance above 0, `max_iterations` may go beyond [`MAX_ITERATIONS`], to
    /// [`MAX_CONVERGENCE_ITERATIONS`]).
    pub fn until_converged(mut self, tolerance: f64, max_iterations: usize) -> Self {
        self.tolerance = tolerance;
        self.iterations = max_iterations;
        self
    }
}

/// Which maps moving least squares fits at each point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MlsVariant {
    /// Rigid motions (the paper's eq. 8; its recommended one, and the default).
    #[default]
    Rigid,
    /// Similarities: rotation, uniform scale, translation (eq. 6).
    Similarity,
    /// Affine maps (eq. 5); needs three handles not all on one line.
    Affine,
}

/// The values [`MlsOptions::alpha`] may take: 0.1 to 4. The weights are
/// `1 / d^(2 alpha)`: towards 0 every handle counts alike and the map tends to one global
/// fit; large powers make each point follow its nearest handle (and `d^(-8)` is already
/// steep enough for any use).
pub const MLS_ALPHA_RANGE: RangeInclusive<f64> = 0.1..=4.0;

/// Moving least squares' settings ([`super::MlsSolver`]), with builders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MlsOptions {
    /// The maps fitted.
    pub variant: MlsVariant,
    /// The weights' falloff: `w_i = 1 / |p_i - v|^(2 alpha)`, in [`MLS_ALPHA_RANGE`]
    /// (default 1, the paper's).
    pub alpha: f64,
}

impl Default for MlsOptions {
    fn default() -> Self {
        Self { variant: MlsVariant::Rigid, alpha: 1.0 }
    }
}

impl Settings for MlsOptions {
    const SETTINGS: &'static [Setting<Self>] = &[
        Setting {
            name: "variant",
            access: Access::Word(
                &["rigid", "similarity", "affine"],
                |o| o.variant as usize,
                |o, i| o.variant = [MlsVariant::Rigid, MlsVariant::Similarity, MlsVariant::Affine][i],
            ),
        },
        Setting { name: "alpha", access: Access::Number(|o| o.alpha, |o, x| o.alpha = x) },
    ];
}

impl MlsOptions {
    /// Sets the variant.
    pub fn with_variant(mut self, variant: MlsVariant) -> Self {
        self.variant = variant;
        self
    }
    /// Sets alpha.
    pub fn with_alpha(mut self, alpha: f64) -> Self {
        self.alpha = alpha;
        self
    }
}

/// The cage sizes [`CauchyGreenOptions::cage`] may ask for: 8 to 1000 vertices. Fewer cannot
/// follow a shape; the set-up grows with the cage's vertices times the mesh's (coordinates
/// at every vertex) and with their cube (the dense smoothness matrix), and a cage of a
/// thousand vertices is already finer than any shape the app meshes needs.
pub const CAGE_VERTICES_RANGE: RangeInclusive<usize> = 8..=1000;

/// The values [`CauchyGreenOptions::smoothness`] may take: 1e-8 to 1e4. The smoothness term
/// is scaled by the cube of the cage's size, so the weight is dimensionless: below the
/// range handles are met to rounding and the map is as wild as the cage allows (and the
/// dense system loses its precision); above, the map is a similarity fitted to the handles.
pub const SMOOTHNESS_RANGE: RangeInclusive<f64> = 1e-8..=1e4;

/// Point-to-point Cauchy-Green settings ([`super::CauchyGreenSolver`]), with builders.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CauchyGreenOptions {
    /// The automatic cage's vertex count, in [`CAGE_VERTICES_RANGE`] (default 64): the map's
    /// degrees of freedom. Ignored while a cage given with `set_cage` is in use.
    pub cage: usize,
    /// The weight of the smoothness term, in [`SMOOTHNESS_RANGE`] (default 1e-5): the map's
    /// cage values minimise `sum_k |f(p_k) - q_k|^2 + smoothness D^3 sum_e sum_(t = 1/4, 3/4)
    /// |e|/2 |f''(z_e(t))|^2`, handles `p_k` to targets `q_k`, `D` the diagonal of the
    /// cage's bounding box, `e` its edges and `z_e(t)` the points at a quarter and three
    /// quarters along them.
    pub smoothness: f64,
}

impl Default for CauchyGreenOptions {
    fn default() -> Self {
        Self { cage: 64, smoothness: 1e-5 }
    }
}

impl Settings for CauchyGreenOptions {
    const SETTINGS: &'static [Setting<Self>] = &[
        Setting { name: "cage", access: Access::Whole(|o| o.cage, |o, n| o.cage = n) },
        Setting { name: "smoothness", access: Access::Number(|o| o.smoothness, |o, x| o.smoothness = x) },
    ];
}

impl CauchyGreenOptions {
    /// Sets the automatic cage's vertex count.
    pub fn with_cage(mut self, vertices: usize) -> Self {
        self.cage = vertices;
        self
    }
    /// Sets the smoothness weight.
    pub fn with_smoothness(mut self, smoothness: f64) -> Self {
        self.smoothness = smoothness;
        self
    }
}
