//! Poses an OBJ mesh with AKAP (or ARAP) and writes the posed mesh as an OBJ, natively:
//! the crate on its own, no JavaScript.
//!
//! ```text
//! cargo run --release --example pose_obj -- OUT.obj     # the built-in figure raises its arm
//! cargo run --release --example pose_obj -- IN.obj OUT.obj --pin 12 --move 40:0.3,0.1
//! cargo run --release --example pose_obj -- --help
//! ```
//!
//! `--pin I` holds vertex I (numbered from 0, in the order of the `v` lines) where it is,
//! `--move I:DX,DY` takes it by (DX, DY). As in the app, moves are split into steps of at
//! most 2% of the mesh's size, each aiming the handles at what is left of their way over the
//! steps left. [`pose_obj`] loads, poses and writes; any error exits with status 1.

use std::fs;
use std::path::PathBuf;
use std::time::Instant;

use akap::deform::{Deformer, Method, MethodOptions, Metrics, SettingValue};
use akap::geometry::Point;
use akap::import::mesh_file::{read_obj, write_obj_pose};
use akap::import::Limits;
use akap::pose::Poser;
use akap::triangulate::triangulate_to_about;
use akap::{shapes, Mesh, TriangulationOptions};

const USAGE: &str = "\
Poses a 2D triangle mesh with AKAP (As-Killing-As-Possible) and writes it as an OBJ.

usage: pose_obj [IN.obj|-] OUT.obj [--pin I]... [--move I:DX,DY]... [options]

  IN.obj          flat OBJ mesh in the xy plane, counter-clockwise triangles
                  (none or `-`: the built-in gingerbread figure, ~1,500 vertices)
  OUT.obj         where to write the posed mesh (texture coordinates kept)
  --pin I         hold vertex I (numbered from 0) where it is
  --move I:DX,DY  move vertex I by (DX, DY), in the mesh's units
  --steps N       deformer steps (default: each moves a handle at most 2% of the mesh's size)
  --method M      akap (default) or arap
  --set NAME=V    a setting of the method, as the JavaScript API names them:
                  akap: lambda=L (1e-6 to 1e10, default 100), dirichlet=true|false,
                        integrator=spiral|linear; arap: iterations=N (1 to 1000, default 10)
  --lambda L      the same as --set lambda=L
  -h, --help      this text

With the built-in figure and no handles, its feet are pinned and its raised hand moved.
";

/// Most steps a pose may take (moves far larger than the mesh need more).
const MAX_STEPS: usize = 100_000;

/// The handles, how far they move, in how many steps, and with which method.
#[derive(Debug, Clone, Default)]
pub(crate) struct Pose {
    /// Vertices held where they are.
    pub(crate) pins: Vec<u32>,
    /// Vertices moved, each with its displacement.
    pub(crate) moves: Vec<(u32, Point)>,
    /// Steps to take; `None` for as many as the tracking takes (steps of at most 2% of the
    /// mesh's size, `Tracking::max_step`).
    pub(crate) steps: Option<usize>,
    /// The method and its settings.
    pub(crate) method: MethodOptions,
}

/// What [`pose_obj`] did.
#[derive(Debug)]
pub(crate) struct Posed {
    /// The posed mesh as OBJ text.
    pub(crate) obj: String,
    /// What was read, and the handles used (the figure's own if none were given).
    pub(crate) vertices: usize,
    pub(crate) triangles: usize,
    pub(crate) has_uvs: bool,
    pub(crate) pose: Pose,
    pub(crate) steps: usize,
    /// Milliseconds: building the deformer, then all the steps.
    pub(crate) setup_ms: f64,
    pub(crate) steps_ms: f64,
    /// Distortion of the result against the input.
    pub(crate) metrics: Metrics,
    /// The largest distance between a handle and its target at the end.
    pub(crate) miss: f64,
}

/// Loads an OBJ (`None`: the built-in figure), poses it as `pose` says and returns the
/// posed mesh as OBJ text with the input's texture coordinates.
pub(crate) fn pose_obj(obj: Option<&str>, pose: &Pose) -> Result<Posed, String> {
    let limits = Limits::default();
    let (mesh, uvs, pose) = match obj {
        Some(text) => {
            let file = read_obj(text, &limits).map_err(|e| format!("not a mesh we can read: {e}"))?;
            (file.mesh, file.uvs, pose.clone())
        }
        None => figure(pose)?,
    };
    let n = mesh.vertex_count();
    let handles: Vec<u32> = pose.pins.iter().chain(pose.moves.iter().map(|m| &m.0)).copied().collect();
    if handles.is_empty() {
        return Err("no handles: give --pin and --move (see --help)".into());
    }
    let mut seen = vec![false; n];
    for &v in &handles {
        if v as usize >= n {
            return Err(format!("vertex {v} is out of range: the mesh has {n} vertices, 0 to {}", n - 1));
        }
        if std::mem::replace(&mut seen[v as usize], true) {
            return Err(format!("vertex {v} has two handles (--pin and --move take each vertex once)"));
        }
    }
    let rest = mesh.positions();
    let targets: Vec<Point> = (pose.pins.iter().map(|&v| (v, [0.0, 0.0])).chain(pose.moves.iter().copied()))
        .map(|(v, d)| [rest[v as usize][0] + d[0], rest[v as usize][1] + d[1]])
        .collect();
    let (vertices, triangles) = (n, mesh.triangle_count());

    let start = Instant::now();
    let mut poser = Poser::new(Deformer::new(mesh, pose.method).map_err(|e| e.to_string())?);
    poser.set_handle_vertices(&handles).map_err(|e| e.to_string())?;
    poser.set_targets(&targets).map_err(|e| e.to_string())?;
    let setup_ms = start.elapsed().as_secs_f64() * 1e3;
    // As many steps as the app's tracking would take (steps of at most 2% of the mesh's
    // size), all of them, not a frame's worth.
    let steps = match pose.steps {
        Some(steps) => steps as f64,
        None => poser.substeps_needed(),
    };
    if !(1.0..=MAX_STEPS as f64).contains(&steps) {
        return Err(format!(
            "{steps} steps: 1 to {MAX_STEPS} can be taken (moves over 2,000 times the mesh's size need more)"
        ));
    }
    let steps = steps as usize;
    let start = Instant::now();
    for step in 0..steps {
        // What is left of each handle's way, over the steps left (the app's tracking).
        let left = (steps - step) as f64;
        poser.step_toward(left, None).map_err(|e| format!("step {} of {steps} failed: {e}", step + 1))?;
    }
    let steps_ms = start.elapsed().as_secs_f64() * 1e3;

    let deformer = poser.deformer();
    let metrics = deformer.metrics();
    let miss = (deformer.handle_positions().iter().zip(&targets))
        .fold(0.0f64, |m, (p, t)| m.max((p[0] - t[0]).hypot(p[1] - t[1])));
    // The pose as it is, flipped triangles included (the summary counts them).
    let obj = write_obj_pose(deformer.positions(), deformer.mesh().triangles(), uvs.as_deref(), None, &limits)
        .map_err(|e| e.to_string())?;
    Ok(Posed { obj, vertices, triangles, has_uvs: uvs.is_some(), pose, steps, setup_ms, steps_ms, metrics, miss })
}

/// The built-in figure, triangulated as the app does (about 1,500 vertices, angles of at
/// least 28 degrees), and `pose`, or with no handles in it, feet pinned and hand raised.
fn figure(pose: &Pose) -> Result<(Mesh, Option<Vec<Point>>, Pose), String> {
    let options = TriangulationOptions::default().with_min_angle_degrees(28.0);
    let (mesh, _) = triangulate_to_about(&shapes::gingerbread(), 1500, &options).map_err(|e| e.to_string())?;
    let mut pose = pose.clone();
    if pose.pins.is_empty() && pose.moves.is_empty() {
        let nearest = |at: Point| {
            let d = |v: &usize| (mesh.positions()[*v][0] - at[0]).hypot(mesh.positions()[*v][1] - at[1]);
            (0..mesh.vertex_count()).min_by(|a, b| d(a).total_cmp(&d(b))).map_or(0, |v| v as u32)
        };
        pose.pins = vec![nearest([0.21, -0.02]), nearest([-0.21, -0.02])];
        pose.moves = vec![(nearest([-0.48, 1.23]), [0.25, 0.05])];
    }
    Ok((mesh, None, pose))
}

/// A setting's value as written on the command line: `true`, `false`, a number or a word.
fn setting_value(text: &str) -> SettingValue {
    match text {
        "true" => SettingValue::Bool(true),
        "false" => SettingValue::Bool(false),
        _ => text.parse().map_or_else(|_| SettingValue::Word(text.into()), SettingValue::Number),
    }
}

/// What to read (`None`: the built-in figure), where to write and how to pose; `None` for help.
type Command = Option<(Option<PathBuf>, PathBuf, Pose)>;

fn parse_args(args: &[String]) -> Result<Command, String> {
    let vertex = |s: &str| s.parse::<u32>().map_err(|_| format!("`{s}` is not a vertex number (0, 1, 2, ...)"));
    let number = |s: &str| match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("`{s}` is not a finite number")),
    };
    let (mut files, mut pose, mut method, mut settings) = (Vec::new(), Pose::default(), None, Vec::new());
    let mut args = args.iter();
    while let Some(arg) = args.next() {
        let mut value = || args.next().map(String::as_str).ok_or_else(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "-h" | "--help" => return Ok(None),
            "--pin" => pose.pins.push(vertex(value()?)?),
            "--move" => {
                let text = value()?;
                let bad = || format!("--move takes VERTEX:DX,DY, like 40:0.3,-0.1, not `{text}`");
                let (v, d) = text.split_once(':').ok_or_else(bad)?;
                let (dx, dy) = d.split_once(',').ok_or_else(bad)?;
                pose.moves.push((vertex(v)?, [number(dx)?, number(dy)?]));
            }
            "--steps" => {
                let text = value()?;
                pose.steps = Some(text.parse().map_err(|_| format!("--steps takes a whole number, not `{text}`"))?);
            }
            "--method" => method = Some(Method::from_name(value()?).map_err(|e| e.to_string())?),
            "--set" => {
                let text = value()?;
                let (name, v) = text.split_once('=').ok_or_else(|| format!("--set takes NAME=VALUE, not `{text}`"))?;
                settings.push((name.to_owned(), setting_value(v)));
            }
            "--lambda" => settings.push(("lambda".into(), SettingValue::Number(number(value()?)?))),
            flag if flag.starts_with('-') && flag != "-" => {
                return Err(format!("unknown option `{flag}` (see --help)"))
            }
            file => files.push(file),
        }
    }
    let values = settings.iter().map(|(name, value)| (name.as_str(), value));
    pose.method = MethodOptions::over(MethodOptions::default(), method, values).map_err(|e| e.to_string())?;
    let (input, output) = match files[..] {
        [output] => (None, output),
        [input, output] => ((input != "-").then(|| input.into()), output),
        [] => return Err("no output file given (see --help)".into()),
        _ => return Err(format!("{} files given: at most IN.obj and OUT.obj (see --help)", files.len())),
    };
    Ok(Some((input, output.into(), pose)))
}

/// Runs a command line (without the program's name): reads, poses and writes, and returns
/// the text to print.
pub(crate) fn run(args: &[String]) -> Result<String, String> {
    let Some((input, output, pose)) = parse_args(args)? else { return Ok(USAGE.into()) };
    let text = match &input {
        Some(path) => Some(fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?),
        None => None,
    };
    let posed = pose_obj(text.as_deref(), &pose).map_err(|e| match &input {
        Some(path) => format!("{}: {e}", path.display()),
        None => e,
    })?;
    fs::write(&output, &posed.obj).map_err(|e| format!("cannot write {}: {e}", output.display()))?;

    let settings: Vec<String> =
        posed.pose.method.values().iter().map(|(name, value)| format!("{name} {value}")).collect();
    let method = format!("{}, {}", posed.pose.method.method(), settings.join(", "));
    let Metrics { area_distortion, angle_distortion, flipped } = posed.metrics;
    let source = input.map_or("the built-in gingerbread figure".into(), |p| p.display().to_string());
    let uvs = if posed.has_uvs { ", texture coordinates kept" } else { "" };
    Ok(format!(
        "read {source}: {} vertices, {} triangles\n\
         handles: pinned {:?}, moved (vertex, by) {:?}\n\
         posed ({method}): set-up {:.1} ms, {} steps in {:.1} ms\n\
         handles end within {:.2e} of their targets\n\
         distortion against the input: area {area_distortion:.4}, angle {angle_distortion:.4} \
         (2 is rigid), {flipped} triangles flipped\n\
         wrote {}{uvs}\n",
        posed.vertices,
        posed.triangles,
        posed.pose.pins,
        posed.pose.moves,
        posed.setup_ms,
        posed.steps,
        posed.steps_ms,
        posed.miss,
        output.display(),
    ))
}

fn main() {
    let args: Result<Vec<String>, _> = std::env::args_os().skip(1).map(|a| a.into_string()).collect();
    let result = args.map_err(|a| format!("argument {a:?} is not valid UTF-8")).and_then(|args| run(&args));
    match result {
        Ok(text) => print!("{text}"),
        Err(e) => {
            eprintln!("pose_obj: {e}");
            std::process::exit(1);
        }
    }
}
