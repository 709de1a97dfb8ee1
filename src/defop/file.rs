//! Operator files: a trained operator with its mesh, in a compact versioned binary, so that
//! a rig trained once poses anywhere without training (the widget, other tools; the
//! dependency-free TypeScript reader in `www/src/defop-file.ts` reads the same layout).
//!
//! All numbers little-endian; offsets in bytes. Version 4, written by [`write_operator`]:
//!
//! | offset | size | field |
//! |---|---|---|
//! | 0 | 8 | magic `AKAPDEFO` |
//! | 8 | 4 | version, 4 (older versions below) |
//! | 12 | 4 | N, vertices |
//! | 16 | 4 | F, triangles |
//! | 20 | 4 | n, handles |
//! | 24 | 4 | m, TPS centres (0 for a polynomial basis) |
//! | 28 | 4 | \|Φ\|, spatial functions (N for the hat functions) |
//! | 32 | 1 | basis: 0 linear, 1 quadratic, 2 cubic, 3 TPS |
//! | 33 | 1 | spatial: 0 hat functions, 1 reduced |
//! | 34 | 1 | solver of the fit: 0 structured, 1 TPS interpolation |
//! | 35 | 1 | handle coordinates: 0 all (or fixed handles), 1 canonical |
//! | 36 | 4 | f, fixed handles (u32) |
//! | 40 | 8 | scale r_s of the handle coordinates (f64) |
//! | 48 | 1 | precision of the operator's numbers (coefficients, D): 0 double (f64, 8 bytes each), 1 single (f32, 4 bytes each) |
//! | 49 | 1 | puppet: 0 none, 1 its section follows the operator |
//! | 50 | 1 | training: 0 not known (bytes 51 to 80 zero), 1 known, below |
//! | 51 | 1 | the training's energy: 0 S-ARAP, 1 ARAP |
//! | 52 | 1 | the training's sampling: 0 discs, 1 Voronoi cells, 2 mixed |
//! | 53 | 3 | zero |
//! | 56 | 4 | the training's samples beyond the rest pose (u32, 1 to 100,000) |
//! | 60 | 4 | zero |
//! | 64 | 8 | the training's seed (u64) |
//! | 72 | 8 | the training's sampling radius (f64, positive) |
//! | 80 | 16 N | vertex positions, x and y (f64) |
//! | | 12 F | triangles, 3 vertex indices each (u32) |
//! | | 32 n | handles: kind (u32: 0 vertex, 1 in a triangle), index (u32: vertex or triangle), 3 barycentric coordinates (f64; 1, 0, 0 for a vertex) |
//! | | 16 n | the handles' rest positions, x and y (f64) |
//! | | 4 f | the fixed handles' indices, ascending (u32) |
//! | | 8 k m | TPS centres in scaled coordinates (f64), k = 2(n − f), or 2n − 3 canonical (0 for n = 1) |
//! | | 2 w \|Φ\| \|Ψ\| | coefficients: for each spatial function, its row of X^x then of X^y (w = 8 or 4 bytes each, byte 48) |
//! | | w \|Φ\| N | reduced basis only: D by vertex, `[v |Φ| + i] = D_iv` (w bytes each) |
//! | | | a puppet's parts and joints (byte 49): |
//! | | 4 | P, parts (u32, 1 to 256) |
//! | | 4 | J, joints (u32, at most N) |
//! | | 12 + L + 4 T per part | depth (i32), T its triangles' count (u32), L its name's length in bytes (u32, at most 1024), the name (UTF-8), its triangles (u32) |
//! | | 24 J | joints: point x, y (f64), front part, back part (u32) |
//! | end − 8 | 8 | FNV-1a 64 of every byte before it |
//!
//! The handle basis, the spatial basis, canonical coordinates and fixed handles of the
//! training are the operator's own fields; bytes 50 to 80 keep the rest of it
//! ([`Operator::training`]). Single precision halves a file (its coefficients and D are
//! most of it): each number is the f64's nearest f32, read back into the f64 operator
//! exactly as that f32.
//!
//! Older versions read, with the training not known: version 2 is version 4 without bytes
//! 48 to 80 (the body starts at 48, double precision, no puppet); version 3 is version 2
//! with a puppet's section before the checksum; version 1 is version 2 with bytes 35 to 40
//! zero (no canonical flag, no fixed handles).
//!
//! Evaluation: u = Bᵀ(q̂ − rest) / r_s (multiplied by 1/r_s), B and q̂ as `coordinates`
//! defines them (B = I and q̂ = q without canonical coordinates or fixed handles; fixed
//! handles' coordinates left out; canonical: q̂ = R*ᵀ(q − c_Q) + c_P and every position
//! moved back, R*(x − c_P) + c_Q); Ψ = 1, u, then the monomials
//! u_a u_b (a ≤ b), u_a u_b u_c (a ≤ b ≤ c) in that nesting order, or for TPS `s log(s)
//! / 2` (0 at 0) of the squared distances s from u to each centre; each spatial function's
//! value is its row of X dotted with Ψ; a vertex's position is that value (hat functions)
//! or D's column dotted with them (reduced).
//!
//! Reading checks everything before using it: the magic, the version, the counts against
//! the limits and the length they imply, the checksum, every flag and code one a writer
//! writes (reserved bytes zero), every number finite, the mesh valid, the handles in
//! range, the puppet fitting the mesh, and the operator's sizes consistent; a truncated or
//! altered file is an error saying which.

use super::basis::{BasisKind, HandleBasis};
use super::coordinates::HandleCoordinates;
use super::energy::Energy;
use super::fit_error::FitError;
use super::operator::{Operator, Solver};
use super::sampling::{Sampling, MAX_SAMPLES};
use super::spatial::MeshPoint;
use super::training::Training;
use crate::deform::{Joint, Part, Puppet, MAX_PARTS, MAX_PART_NAME_BYTES};
use crate::mesh::{Mesh, DEFAULT_MAX_VERTICES};

/// The first 8 bytes of an operator file.
pub const MAGIC: [u8; 8] = *b"AKAPDEFO";
/// The version this code writes (it reads versions 1 to 4).
pub const VERSION: u32 = 4;
/// The header of versions 1 to 3, and of version 4.
const HEADER_BEFORE_4: usize = 48;
const HEADER: usize = 80;

/// How an operator file stores the operator's numbers (its coefficients and, for a reduced
/// spatial basis, D); everything else is always double precision.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Precision {
    /// 8 bytes each: the operator exactly.
    #[default]
    Double,
    /// 4 bytes each, the nearest f32 of each number: half the size.
    Single,
}

/// The codes the file gives the training's energies and samplings, in one place.
const ENERGIES: [Energy; 2] = [Energy::SArap, Energy::Arap];
const SAMPLINGS: [Sampling; 3] = [Sampling::Disc, Sampling::Voronoi, Sampling::Mixed];

/// Why an operator file could not be read.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum OperatorFileError {
    /// The bytes do not start with [`MAGIC`].
    NotAnOperator,
    /// A version this code does not read.
    Version {
        /// The version found.
        found: u32,
    },
    /// The file is shorter or longer than its counts say.
    Length {
        /// Bytes the counts imply.
        expected: u64,
        /// Bytes given.
        found: usize,
    },
    /// A count is beyond the limits (or zero where one is needed).
    Count {
        /// Which count.
        what: &'static str,
        /// The value.
        value: u64,
    },
    /// The checksum does not match: the file was altered or damaged.
    Checksum,
    /// A field holds a value no writer writes.
    Field {
        /// Which field.
        what: &'static str,
    },
    /// The mesh, the handles or the operator in the file are not consistent.
    Invalid(String),
}

impl std::fmt::Display for OperatorFileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NotAnOperator => f.write_str("not an operator file (it does not start with AKAPDEFO)"),
            Self::Version { found } => {
                let newer = if *found > VERSION { ": a newer version of this program wrote it" } else { "" };
                write!(f, "operator file version {found} is not supported (only 1 to {VERSION}){newer}")
            }
            Self::Length { expected, found } => write!(
                f,
                "the operator file has {found} bytes but its counts need {expected}: it is truncated or altered"
            ),
            Self::Count { what, value } => write!(f, "the operator file's {what} is {value}, beyond the limits"),
            Self::Checksum => f.write_str("the operator file's checksum does not match: it was altered or damaged"),
            Self::Field { what } => write!(f, "the operator file's {what} holds a value no writer writes"),
            Self::Invalid(why) => write!(f, "the operator file is not consistent: {why}"),
        }
    }
}

impl std::error::Error for OperatorFileError {}

/// FNV-1a, 64 bits.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

fn kind_code(kind: BasisKind) -> u8 {
    match kind {
        BasisKind::Linear => 0,
        BasisKind::Quadratic => 1,
        BasisKind::Cubic => 2,
        BasisKind::Tps => 3,
    }
}

/// The operator and its mesh as an operator file (version 4, double precision).
pub fn write_operator(mesh: &Mesh, operator: &Operator) -> Result<Vec<u8>, FitError> {
    write_operator_in(mesh, operator, Precision::Double)
}

/// The operator and its mesh as an operator file (version 4) with the operator's numbers in
/// `precision`. Refuses a mesh that is not the operator's, a puppet that does not fit the
/// mesh, a training out of range, and in single precision a number beyond f32's range.
pub fn write_operator_in(mesh: &Mesh, operator: &Operator, precision: Precision) -> Result<Vec<u8>, FitError> {
    if mesh.vertex_count() != operator.vertex_count() {
        let (expected, found) = (operator.vertex_count(), mesh.vertex_count());
        return Err(FitError::Length { what: "mesh", expected, found });
    }
    let basis = operator.handle_basis();
    let n = operator.handles().len();
    let coordinates = basis.coordinates();
    let m = basis.scaled_centres().len() / coordinates.len().max(1);
    if let Some(puppet) = operator.puppet() {
        check_puppet(puppet, mesh).map_err(FitError::InvalidPuppet)?;
    }
    let training = operator.training();
    if let Some(t) = training {
        check_training(t)?;
    }
    let numbers = operator.coefficients().iter().chain(operator.reduction());
    let single = precision == Precision::Single;
    if let Some(index) = numbers.clone().position(|&x| !(x as f32).is_finite()).filter(|_| single) {
        return Err(FitError::NonFinite { what: "coefficients in single precision", index });
    }
    let mut out = Vec::new();
    out.extend_from_slice(&MAGIC);
    for count in [VERSION as usize, mesh.vertex_count(), mesh.triangle_count(), n, m, operator.spatial_len()] {
        out.extend_from_slice(&(count as u32).to_le_bytes());
    }
    let reduced = !operator.reduction().is_empty();
    let solver = u8::from(operator.solver() == Solver::TpsInterpolation);
    out.extend_from_slice(&[kind_code(basis.kind()), u8::from(reduced), solver, u8::from(coordinates.is_canonical())]);
    out.extend_from_slice(&(coordinates.fixed().len() as u32).to_le_bytes());
    out.extend_from_slice(&basis.scale().to_le_bytes());
    out.extend_from_slice(&[u8::from(single), u8::from(operator.puppet().is_some()), u8::from(training.is_some())]);
    let mut fields = [0u8; HEADER - 51];
    if let Some(t) = training {
        fields[0] = code(&ENERGIES, t.energy);
        fields[1] = code(&SAMPLINGS, t.sampling);
        fields[5..9].copy_from_slice(&(t.samples as u32).to_le_bytes());
        fields[13..21].copy_from_slice(&t.seed.to_le_bytes());
        fields[21..29].copy_from_slice(&t.radius.to_le_bytes());
    }
    out.extend_from_slice(&fields);
    debug_assert_eq!(out.len(), HEADER);
    let f64s = |out: &mut Vec<u8>, values: &mut dyn Iterator<Item = f64>| {
        values.for_each(|x| out.extend_from_slice(&x.to_le_bytes()))
    };
    f64s(&mut out, &mut mesh.positions().iter().flatten().copied());
    mesh.triangles().iter().flatten().for_each(|v| out.extend_from_slice(&v.to_le_bytes()));
    for handle in operator.handles() {
        let (kind, index, weights) = match *handle {
            MeshPoint::Vertex(v) => (0u32, v, [1.0, 0.0, 0.0]),
            MeshPoint::Inside { triangle, barycentric } => (1, triangle, barycentric),
        };
        out.extend_from_slice(&kind.to_le_bytes());
        out.extend_from_slice(&index.to_le_bytes());
        f64s(&mut out, &mut weights.into_iter());
    }
    f64s(&mut out, &mut basis.rest().iter().copied());
    coordinates.fixed().iter().for_each(|&a| out.extend_from_slice(&(a as u32).to_le_bytes()));
    f64s(&mut out, &mut basis.scaled_centres().iter().copied());
    if single {
        numbers.for_each(|&x| out.extend_from_slice(&(x as f32).to_le_bytes()));
    } else {
        f64s(&mut out, &mut numbers.copied());
    }
    if let Some(puppet) = operator.puppet() {
        out.extend_from_slice(&(puppet.parts.len() as u32).to_le_bytes());
        out.extend_from_slice(&(puppet.joints.len() as u32).to_le_bytes());
        for part in &puppet.parts {
            out.extend_from_slice(&part.depth.to_le_bytes());
            out.extend_from_slice(&(part.triangles.len() as u32).to_le_bytes());
            out.extend_from_slice(&(part.name.len() as u32).to_le_bytes());
            out.extend_from_slice(part.name.as_bytes());
            part.triangles.iter().for_each(|t| out.extend_from_slice(&t.to_le_bytes()));
        }
        for joint in &puppet.joints {
            f64s(&mut out, &mut joint.point.into_iter());
            joint.parts.iter().for_each(|&p| out.extend_from_slice(&(p as u32).to_le_bytes()));
        }
    }
    let checksum = fnv1a(&out);
    out.extend_from_slice(&checksum.to_le_bytes());
    Ok(out)
}

/// The file's code of `value`: its place in `all` (every value has one).
fn code<T: PartialEq>(all: &[T], value: T) -> u8 {
    all.iter().position(|y| *y == value).expect("every value has a code") as u8
}

/// Refuses a training a file cannot keep (the reader's checks).
fn check_training(t: &Training) -> Result<(), FitError> {
    if !(1..=MAX_SAMPLES).contains(&t.samples) {
        let expected = "a whole number from 1 to 100000";
        return Err(FitError::InvalidOption { name: "training samples", value: t.samples as f64, expected });
    }
    if !(t.radius.is_finite() && t.radius > 0.0) {
        let expected = "a positive finite length";
        return Err(FitError::InvalidOption { name: "training radius", value: t.radius, expected });
    }
    Ok(())
}

/// Reads an operator file: its mesh and its operator, everything checked.
pub fn read_operator(bytes: &[u8]) -> Result<(Mesh, Operator), OperatorFileError> {
    if bytes.len() < 8 || bytes[..8] != MAGIC {
        return Err(OperatorFileError::NotAnOperator);
    }
    if bytes.len() < 12 {
        return Err(OperatorFileError::Length { expected: (HEADER_BEFORE_4 + 8) as u64, found: bytes.len() });
    }
    let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    let version = u32_at(8);
    if !(1..=VERSION).contains(&version) {
        return Err(OperatorFileError::Version { found: version });
    }
    let header = if version >= 4 { HEADER } else { HEADER_BEFORE_4 };
    if bytes.len() < header + 8 {
        return Err(OperatorFileError::Length { expected: (header + 8) as u64, found: bytes.len() });
    }
    let [nv, nt, n, m, phi] = [12, 16, 20, 24, 28].map(|at| u64::from(u32_at(at)));
    let max_vertices = DEFAULT_MAX_VERTICES as u64;
    let limits = [
        ("vertex count", nv, 3, max_vertices),
        ("triangle count", nt, 1, 2 * max_vertices),
        ("handle count", n, 1, max_vertices),
        ("TPS centre count", m, 0, MAX_SAMPLES as u64 + 1),
        ("spatial basis size", phi, 3, max_vertices),
    ];
    for (what, value, low, high) in limits {
        if !(low..=high).contains(&value) {
            return Err(OperatorFileError::Count { what, value });
        }
    }
    let kind = match bytes[32] {
        0 => BasisKind::Linear,
        1 => BasisKind::Quadratic,
        2 => BasisKind::Cubic,
        3 => BasisKind::Tps,
        _ => return Err(OperatorFileError::Field { what: "basis" }),
    };
    let flag = |at: usize, what: &'static str| match bytes[at] {
        0 => Ok(false),
        1 => Ok(true),
        _ => Err(OperatorFileError::Field { what }),
    };
    let reduced = flag(33, "spatial basis kind")?;
    let solver = if flag(34, "solver")? { Solver::TpsInterpolation } else { Solver::Structured };
    // Version 1 holds zeros where version 2 holds the coordinates' fields: the same file.
    if version == 1 && bytes[35..40].iter().any(|&b| b != 0) {
        return Err(OperatorFileError::Field { what: "reserved bytes" });
    }
    let canonical = flag(35, "handle coordinates")?;
    let f = u64::from(u32_at(36));
    if f > n || (canonical && f > 0) {
        return Err(OperatorFileError::Count { what: "fixed handle count", value: f });
    }
    let (single, has_puppet, training) = if version >= 4 {
        let single = flag(48, "precision")?;
        let has_puppet = flag(49, "puppet flag")?;
        (single, has_puppet, read_training(&bytes[..HEADER])?)
    } else {
        (false, version == 3, None)
    };
    let k = HandleCoordinates::count(n as usize, canonical, f as usize) as u64;
    if (kind == BasisKind::Tps) != (m > 0) || (m > 0 && k == 0) {
        return Err(OperatorFileError::Field { what: "TPS centre count" });
    }
    let psi = kind.size_in(k as usize, m as usize) as u64;
    if psi > super::basis::MAX_BASIS_SIZE as u64 {
        return Err(OperatorFileError::Count { what: "handle basis size", value: psi });
    }
    let width = if single { 4 } else { 8 };
    let expected = header as u64
        + 16 * nv
        + 12 * nt
        + 32 * n
        + 16 * n
        + 4 * f
        + 8 * k * m
        + 2 * width * phi * psi
        + if reduced { width * phi * nv } else { 0 }
        + 8;
    // A puppet's section follows, its length read from it.
    let puppet_bytes = (bytes.len() as u64).saturating_sub(expected);
    if (!has_puppet && expected != bytes.len() as u64) || (has_puppet && puppet_bytes < 8) {
        let expected = expected + if has_puppet { 8 } else { 0 };
        return Err(OperatorFileError::Length { expected, found: bytes.len() });
    }
    let (body, tail) = bytes.split_at(bytes.len() - 8);
    if fnv1a(body) != u64::from_le_bytes(tail.try_into().expect("8 bytes")) {
        return Err(OperatorFileError::Checksum);
    }
    let scale = f64::from_le_bytes(bytes[40..48].try_into().expect("8 bytes"));
    let mut cursor = Cursor { bytes: body, at: header };
    let positions = cursor.f64s(2 * nv);
    let triangles = cursor.u32s(3 * nt);
    let mut handles = Vec::with_capacity(n as usize);
    for _ in 0..n {
        let [kind, index] = [cursor.u32s(1)[0], cursor.u32s(1)[0]];
        let w = cursor.f64s(3);
        handles.push(match kind {
            0 => MeshPoint::Vertex(index),
            1 => MeshPoint::Inside { triangle: index, barycentric: [w[0], w[1], w[2]] },
            _ => return Err(OperatorFileError::Field { what: "handle kind" }),
        });
    }
    let rest = cursor.f64s(2 * n);
    let fixed: Vec<usize> = cursor.u32s(f).into_iter().map(|a| a as usize).collect();
    let centres = cursor.f64s(k * m);
    let numbers = |cursor: &mut Cursor<'_>, count: u64| if single { cursor.f32s(count) } else { cursor.f64s(count) };
    let coefficients = numbers(&mut cursor, 2 * phi * psi);
    let reduction = if reduced { numbers(&mut cursor, phi * nv) } else { Vec::new() };
    let puppet = if has_puppet { Some(read_puppet(&mut cursor, nv)?) } else { None };
    if cursor.at != body.len() {
        return Err(OperatorFileError::Length { expected: (cursor.at + 8) as u64, found: bytes.len() });
    }
    let finite = |values: &[f64]| values.iter().all(|x| x.is_finite());
    let joint_points: Vec<f64> = puppet.iter().flat_map(|p| p.joints.iter().flat_map(|j| j.point)).collect();
    let fields = [&positions, &rest, &centres, &coefficients, &reduction, &joint_points];
    if !(scale.is_finite() && fields.iter().all(|values| finite(values))) {
        return Err(OperatorFileError::Invalid("a number is not finite".into()));
    }
    let invalid = |e: &dyn std::fmt::Display| OperatorFileError::Invalid(e.to_string());
    let mesh = Mesh::from_flat(&positions, &triangles).map_err(|e| invalid(&e))?;
    if let Some(puppet) = &puppet {
        check_puppet(puppet, &mesh).map_err(OperatorFileError::Invalid)?;
    }
    for handle in &handles {
        let fine = match *handle {
            MeshPoint::Vertex(v) => (v as u64) < nv,
            MeshPoint::Inside { triangle, barycentric } => {
                (triangle as u64) < nt
                    && barycentric.iter().all(|w| w.is_finite() && *w >= -1e-12)
                    && (barycentric.iter().sum::<f64>() - 1.0).abs() <= 1e-9
            }
        };
        if !fine {
            return Err(OperatorFileError::Invalid(format!("handle {handle:?} is not a point of the mesh")));
        }
    }
    if !reduced && phi != nv {
        return Err(OperatorFileError::Field { what: "spatial basis size" });
    }
    let coordinates = HandleCoordinates::new(&rest, canonical, &fixed).map_err(|e| invalid(&e))?;
    if coordinates.fixed() != fixed.as_slice() {
        return Err(OperatorFileError::Invalid("the fixed handles are not in ascending order".into()));
    }
    let basis = HandleBasis::from_parts(kind, coordinates, scale, centres).map_err(|e| invalid(&e))?;
    let operator = Operator::from_parts(handles, basis, solver, phi as usize, nv as usize, coefficients, reduction)
        .map_err(|e| invalid(&e))?;
    Ok((mesh, operator.with_puppet(puppet).with_training(training)))
}

/// A version-4 header's training (bytes 50 to 80), `None` when not known; every code and
/// reserved byte checked.
fn read_training(header: &[u8]) -> Result<Option<Training>, OperatorFileError> {
    let reserved = |range: std::ops::Range<usize>| header[range].iter().any(|&b| b != 0);
    match header[50] {
        0 if reserved(51..HEADER) => return Err(OperatorFileError::Field { what: "unknown training's bytes" }),
        0 => return Ok(None),
        1 => {}
        _ => return Err(OperatorFileError::Field { what: "training flag" }),
    }
    if reserved(53..56) || reserved(60..64) {
        return Err(OperatorFileError::Field { what: "reserved bytes" });
    }
    let energy = *ENERGIES.get(usize::from(header[51])).ok_or(OperatorFileError::Field { what: "training energy" })?;
    let sampling =
        *SAMPLINGS.get(usize::from(header[52])).ok_or(OperatorFileError::Field { what: "training sampling" })?;
    let samples = u32::from_le_bytes(header[56..60].try_into().expect("4 bytes")) as usize;
    if !(1..=MAX_SAMPLES).contains(&samples) {
        return Err(OperatorFileError::Count { what: "training's sample count", value: samples as u64 });
    }
    let seed = u64::from_le_bytes(header[64..72].try_into().expect("8 bytes"));
    let radius = f64::from_le_bytes(header[72..80].try_into().expect("8 bytes"));
    if !(radius.is_finite() && radius > 0.0) {
        return Err(OperatorFileError::Invalid(format!("the training's radius is {radius}, not a positive length")));
    }
    Ok(Some(Training { energy, sampling, samples, radius, seed }))
}

/// Checks a puppet against its mesh as a deformer does, and its sizes as the file's
/// fields allow; the reason if it does not fit.
fn check_puppet(puppet: &Puppet, mesh: &Mesh) -> Result<(), String> {
    if !(1..=MAX_PARTS).contains(&puppet.parts.len()) {
        return Err(format!("the puppet has {} parts, not 1 to {MAX_PARTS}", puppet.parts.len()));
    }
    if puppet.joints.len() > mesh.vertex_count() {
        return Err(format!("the puppet has {} joints, more than its mesh's vertices", puppet.joints.len()));
    }
    if let Some((p, _)) = puppet.parts.iter().enumerate().find(|(_, part)| part.name.len() > MAX_PART_NAME_BYTES) {
        return Err(format!("the name of the puppet's part {p} is longer than {MAX_PART_NAME_BYTES} bytes"));
    }
    puppet.joins(mesh).map(drop).map_err(|e| e.to_string())
}

/// A puppet's section (module documentation), every length checked
/// against what is left before the checksum.
fn read_puppet(cursor: &mut Cursor<'_>, vertices: u64) -> Result<Puppet, OperatorFileError> {
    let short = |cursor: &Cursor<'_>| {
        OperatorFileError::Invalid(format!("the puppet's section ends before its counts say (at byte {})", cursor.at))
    };
    let count = |cursor: &mut Cursor<'_>| -> Result<u64, OperatorFileError> {
        if cursor.left() < 4 {
            return Err(short(cursor));
        }
        Ok(u64::from(cursor.u32s(1)[0]))
    };
    let parts = count(cursor)?;
    let joints = count(cursor)?;
    if !(1..=MAX_PARTS as u64).contains(&parts) {
        return Err(OperatorFileError::Count { what: "puppet's part count", value: parts });
    }
    if joints > vertices {
        return Err(OperatorFileError::Count { what: "puppet's joint count", value: joints });
    }
    let mut puppet = Puppet::default();
    for _ in 0..parts {
        let depth = count(cursor)? as u32 as i32;
        let triangles = count(cursor)?;
        let name = count(cursor)?;
        if name > MAX_PART_NAME_BYTES as u64 {
            return Err(OperatorFileError::Count { what: "puppet's part name length", value: name });
        }
        if (cursor.left() as u64) < name + 4 * triangles {
            return Err(short(cursor));
        }
        let name = String::from_utf8(cursor.take(name as usize).to_vec())
            .map_err(|_| OperatorFileError::Invalid("a part's name is not UTF-8".into()))?;
        puppet.parts.push(Part { name, triangles: cursor.u32s(triangles), depth });
    }
    if (cursor.left() as u64) < 24 * joints {
        return Err(short(cursor));
    }
    for _ in 0..joints {
        let p = cursor.f64s(2);
        let [front, back] = [0, 1].map(|_| cursor.u32s(1)[0] as usize);
        puppet.joints.push(Joint { point: [p[0], p[1]], parts: [front, back] });
    }
    Ok(puppet)
}

/// Reads little-endian numbers in order (every length was checked beforehand).
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Cursor<'_> {
    /// The bytes left.
    fn left(&self) -> usize {
        self.bytes.len() - self.at
    }

    fn take(&mut self, len: usize) -> &[u8] {
        let taken = &self.bytes[self.at..self.at + len];
        self.at += len;
        taken
    }

    fn f64s(&mut self, count: u64) -> Vec<f64> {
        self.take(8 * count as usize).chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().expect("8"))).collect()
    }

    /// Single-precision numbers, each read back as the f64 of the same value.
    fn f32s(&mut self, count: u64) -> Vec<f64> {
        let f32 = |c: &[u8]| f64::from(f32::from_le_bytes(c.try_into().expect("4")));
        self.take(4 * count as usize).chunks_exact(4).map(f32).collect()
    }

    fn u32s(&mut self, count: u64) -> Vec<u32> {
        self.take(4 * count as usize).chunks_exact(4).map(|c| u32::from_le_bytes(c.try_into().expect("4"))).collect()
    }
}
