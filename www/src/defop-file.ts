/**
 * Operator files without WebAssembly: reads the file {@link DefOp.toBytes} writes (the
 * layout is documented once, in Rust's `akap::defop::file`) and poses its mesh, in plain
 * TypeScript that imports nothing, for game engines and tools that cannot load wasm. It
 * agrees with the wasm evaluator to rounding (about 1e-15 of the shape's size).
 *
 * @example
 * ```ts
 * import { readOperatorFile } from "akap";
 * const rig = readOperatorFile(new Uint8Array(await (await fetch("rig.defop")).arrayBuffer()));
 * const posed = new Float64Array(2 * rig.vertexCount);
 * rig.evaluateInto(targets, posed); // 2 numbers per handle in, 2 per vertex out
 * ```
 */

/** A deformation operator read from its file, with its mesh. */
export interface OperatorFile {
  /** The mesh at rest: x and y per vertex. */
  readonly positions: Float64Array;
  /** Counter-clockwise index triples. */
  readonly triangles: Uint32Array;
  readonly vertexCount: number;
  /** Handles: 2 target numbers each. */
  readonly handleCount: number;
  /** The handles' rest positions (x and y each): the targets that give the rest pose. */
  readonly rest: Float64Array;
  /** Whether the operator is canonical: a rigid motion of all targets moves the pose rigidly. */
  readonly canonical: boolean;
  /** Handles held at rest (ascending): their targets are ignored. */
  readonly fixed: Uint32Array;
  /** The parts of the puppet the operator was trained on (a file of version 3, or 4 with the puppet flag), else
   * `undefined`: `triangles` are indices of the mesh's triangles, larger `depth` in front. */
  readonly parts?: { name: string; triangles: Uint32Array; depth: number }[];
  /** The puppet's joints (with its parts), `parts` `[front, back]`, else `undefined`. */
  readonly joints?: { point: [number, number]; parts: [number, number] }[];
  /**
   * The settings it was trained with (a version-4 file that knows them; as `DefOp.training`
   * gives them), else `undefined`.
   */
  readonly training?: {
    energy: "sarap" | "arap";
    basis: "linear" | "quadratic" | "cubic" | "tps";
    /** 0: the hat functions; else the size of the reduced spatial basis. */
    spatial: number;
    samples: number;
    sampling: "disc" | "voronoi" | "mixed";
    radius: number;
    seed: number;
    canonical: boolean;
    fixed: Uint32Array;
  };
  /** How the file stores the coefficients: `"single"` (32-bit floats, read back exactly as those) or `"double"`. */
  readonly precision: "double" | "single";
  /** Writes the vertex positions (2 per vertex) for handle targets (2 per handle) to `out`. */
  evaluateInto(targets: ArrayLike<number>, out: Float64Array): void;
}

const MAGIC = "AKAPDEFO";
/** The header of versions 1 to 3, and of version 4. */
const HEADER_BEFORE_4 = 48;
const HEADER = 80;

/** FNV-1a, 64 bits, of `bytes`, in two 32-bit halves (high, low). */
function fnv1a(bytes: Uint8Array): [number, number] {
  let hi = 0xcbf29ce4;
  let lo = 0x84222325;
  for (const byte of bytes) {
    lo = (lo ^ byte) >>> 0;
    // Multiply (hi, lo) by the prime 0x100000001b3 = 2^40 + 0x1b3, modulo 2^64.
    const a = lo * 0x1b3;
    const carry = Math.floor(a / 0x100000000);
    const newLo = a >>> 0;
    const newHi = (hi * 0x1b3 + carry + ((lo << 8) >>> 0)) >>> 0;
    hi = newHi;
    lo = newLo;
  }
  return [hi >>> 0, lo >>> 0];
}

/**
 * The handle coordinates z = Bᵀ(Q̂ − P) of Rust's `akap::defop::coordinates`, computed the
 * same way: the free coordinates (all but the fixed handles'), and for a canonical
 * operator the Householder vectors of the two translations and the rotation about the
 * rest handles' centroid.
 */
class Coordinates {
  readonly free: number[];
  readonly reflectors: Float64Array[] = [];
  readonly gram: number[][] = [];
  readonly centroid: [number, number];
  readonly alpha = [0, 0, 0];
  constructor(
    readonly rest: Float64Array,
    readonly canonical: boolean,
    fixed: Uint32Array,
  ) {
    const n = rest.length / 2;
    const isFixed = new Set(fixed);
    this.free = [];
    for (let c = 0; c < 2 * n; c++) if (!isFixed.has(c >> 1)) this.free.push(c);
    const invN = 1 / n;
    const sum = (nu: number) => {
      let s = 0;
      for (let a = nu; a < 2 * n; a += 2) s += rest[a]!;
      return s;
    };
    this.centroid = [sum(0) * invN, sum(1) * invN];
    const columns: Float64Array[] = [];
    if (canonical) {
      const s = Math.sqrt(invN);
      columns.push(Float64Array.from({ length: 2 * n }, (_, c) => (c % 2 === 0 ? s : 0)));
      columns.push(Float64Array.from({ length: 2 * n }, (_, c) => (c % 2 === 1 ? s : 0)));
      if (n >= 2) {
        const r = new Float64Array(2 * n);
        for (let a = 0; a < n; a++) {
          r[2 * a] = -(rest[2 * a + 1]! - this.centroid[1]);
          r[2 * a + 1] = rest[2 * a]! - this.centroid[0];
        }
        let norm = 0;
        for (const x of r) norm += x * x;
        norm = Math.sqrt(norm);
        if (norm === 0) throw new Error("not a usable operator file: its rest handles are all at one point");
        columns.push(r.map((x) => x / norm));
      }
    }
    // Householder QR of the columns, as Rust's `householder`.
    for (let j = 0; j < columns.length; j++) {
      const x = columns[j]!;
      let sigma = 0;
      for (let i = j; i < x.length; i++) sigma += x[i]! * x[i]!;
      sigma = Math.sqrt(sigma);
      const alpha = x[j]! >= 0 ? -sigma : sigma;
      const v = x.slice();
      v.fill(0, 0, j);
      v[j] = v[j]! - alpha;
      let norm = 0;
      for (let i = j; i < v.length; i++) norm += v[i]! * v[i]!;
      norm = Math.sqrt(norm);
      for (let i = j; i < v.length; i++) v[i] = v[i]! / norm;
      for (const column of columns.slice(j + 1)) {
        let d = 0;
        for (let i = j; i < v.length; i++) d += v[i]! * column[i]!;
        const s = 2 * d;
        for (let i = j; i < v.length; i++) column[i] = column[i]! - s * v[i]!;
      }
      this.reflectors.push(v);
    }
    for (let r = 0; r < this.reflectors.length; r++) {
      this.gram.push([]);
      for (let s = 0; s < r; s++) {
        let d = 0;
        const [a, b] = [this.reflectors[r]!, this.reflectors[s]!];
        for (let i = 0; i < a.length; i++) d += a[i]! * b[i]!;
        this.gram[r]!.push(d);
      }
    }
  }

  /** k, the number of coordinates. */
  get length(): number {
    return this.free.length - this.reflectors.length;
  }

  /** Writes Bᵀ(targets − P) · inv to `out` from index `at` on. */
  project(targets: ArrayLike<number>, inv: number, out: Float64Array, at: number): void {
    const { free, rest, reflectors, gram, alpha } = this;
    const w = (i: number) => targets[free[i]!]! - rest[free[i]!]!;
    const c = reflectors.length;
    for (let r = 0; r < c; r++) {
      const v = reflectors[r]!;
      let a = 0;
      for (let i = r; i < v.length; i++) a += v[i]! * w(i);
      for (let s = 0; s < r; s++) a -= 2 * alpha[s]! * gram[r]![s]!;
      alpha[r] = a;
    }
    for (let j = 0; j < this.length; j++) {
      let x = w(c + j);
      for (let r = 0; r < c; r++) x -= 2 * alpha[r]! * reflectors[r]![c + j]!;
      out[at + j] = x * inv;
    }
  }

  /** Writes the canonical targets Q̂ to `out`; returns [cos, sin, c_Q x, c_Q y] of the motion back. */
  canonicalise(targets: ArrayLike<number>, out: Float64Array): [number, number, number, number] {
    const { rest, centroid } = this;
    const n = rest.length / 2;
    const invN = 1 / n;
    let [tx, ty] = [0, 0];
    for (let a = 0; a < n; a++) [tx, ty] = [tx + targets[2 * a]!, ty + targets[2 * a + 1]!];
    [tx, ty] = [tx * invN, ty * invN];
    let [dot, cross] = [0, 0];
    for (let a = 0; a < n; a++) {
      const [px, py] = [rest[2 * a]! - centroid[0], rest[2 * a + 1]! - centroid[1]];
      const [qx, qy] = [targets[2 * a]! - tx, targets[2 * a + 1]! - ty];
      dot += px * qx + py * qy;
      cross += px * qy - py * qx;
    }
    const h = Math.hypot(dot, cross);
    const [cos, sin] = h > 0 ? [dot / h, cross / h] : [1, 0];
    for (let a = 0; a < n; a++) {
      const [px, py] = [rest[2 * a]!, rest[2 * a + 1]!];
      const [qx, qy] = [targets[2 * a]! - tx, targets[2 * a + 1]! - ty];
      out[2 * a] = px + (cos * qx + sin * qy - (px - centroid[0]));
      out[2 * a + 1] = py + (-sin * qx + cos * qy - (py - centroid[1]));
    }
    return [cos, sin, tx, ty];
  }
}

/** Reads and checks an operator file; throws an `Error` saying what is wrong. */
export function readOperatorFile(bytes: Uint8Array): OperatorFile {
  const fail = (why: string): never => {
    throw new Error(`not a usable operator file: ${why}`);
  };
  if (bytes.length < HEADER_BEFORE_4 + 8 || String.fromCharCode(...bytes.subarray(0, 8)) !== MAGIC)
    fail("no AKAPDEFO header");
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const u32 = (at: number) => view.getUint32(at, true);
  const version = u32(8);
  if (version < 1 || version > 4) fail(`version ${version} (only 1 to 4 are read)`);
  const header = version >= 4 ? HEADER : HEADER_BEFORE_4;
  if (bytes.length < header + 8) fail(`${bytes.length} bytes, fewer than its header`);
  const [nv, nt, n, m, phi] = [12, 16, 20, 24, 28].map(u32) as [number, number, number, number, number];
  // Version 1 holds zeros where version 2 holds the canonical flag and the fixed count.
  const [kind, reduced, canonical, f] = [bytes[32]!, bytes[33]!, bytes[35]!, u32(36)];
  if (kind > 3 || reduced > 1 || canonical > 1 || n === 0 || nv < 3 || f > n || (canonical && f > 0))
    fail("a field holds a value no writer writes");
  if (version === 1 && (canonical || f)) fail("a version-1 file with version-2 fields");
  // Version 4: precision, puppet and training flags, and the training (Rust's layout).
  const [single, hasPuppet, known] =
    version >= 4 ? [bytes[48]!, bytes[49]!, bytes[50]!] : [0, version === 3 ? 1 : 0, 0];
  if (single > 1 || hasPuppet > 1 || known > 1) fail("a flag holds a value no writer writes");
  const reserved = (from: number, to: number) => bytes.subarray(from, to).some((b) => b !== 0);
  if (version >= 4 && (known ? reserved(53, 56) || reserved(60, 64) : reserved(51, HEADER)))
    fail("a reserved byte is not zero");
  const energy = (["sarap", "arap"] as const)[bytes[51]!];
  const sampling = (["disc", "voronoi", "mixed"] as const)[bytes[52]!];
  const [samples, seed, radius] = [u32(56), Number(view.getBigUint64(64, true)), view.getFloat64(72, true)];
  if (known && (!energy || !sampling || samples < 1 || samples > 100_000 || !(radius > 0 && radius < Infinity)))
    fail("the training's fields hold values no writer writes");
  const d = 2 * n;
  // k, the handle coordinates: 2(n − f), or 2n − 3 canonical (0 for one handle).
  const k = 2 * (n - f) - (canonical ? (n >= 2 ? 3 : 2) : 0);
  const psi = [k + 1, 1 + k + (k * (k + 1)) / 2, 1 + k + (k * (k + 1)) / 2 + (k * (k + 1) * (k + 2)) / 6, k + 1 + m][
    kind
  ]!;
  const width = single ? 4 : 8;
  const expected =
    header +
    16 * nv +
    12 * nt +
    48 * n +
    4 * f +
    8 * k * m +
    2 * width * phi * psi +
    (reduced ? width * phi * nv : 0) +
    8;
  // A puppet's section follows, its length read from it.
  if (hasPuppet ? bytes.length < expected + 8 : bytes.length !== expected)
    fail(`${bytes.length} bytes where its counts need ${expected}`);
  const [hi, lo] = fnv1a(bytes.subarray(0, bytes.length - 8));
  if (u32(bytes.length - 8) !== lo || u32(bytes.length - 4) !== hi) fail("the checksum does not match");

  let at = header;
  const f64s = (count: number) => {
    const out = new Float64Array(count);
    for (let k = 0; k < count; k++, at += 8) out[k] = view.getFloat64(at, true);
    return out;
  };
  /** The operator's numbers, in the file's precision. */
  const numbers = (count: number) => {
    if (!single) return f64s(count);
    const out = new Float64Array(count);
    for (let k = 0; k < count; k++, at += 4) out[k] = view.getFloat32(at, true);
    return out;
  };
  const scale = view.getFloat64(40, true);
  const positions = f64s(2 * nv);
  const triangles = new Uint32Array(3 * nt);
  for (let k = 0; k < 3 * nt; k++, at += 4) triangles[k] = u32(at);
  at += 32 * n; // the handles' places on the mesh: not needed to evaluate
  const rest = f64s(d);
  const fixed = new Uint32Array(f);
  for (let a = 0; a < f; a++, at += 4) fixed[a] = u32(at);
  const centres = f64s(k * m);
  const coordinates = new Coordinates(rest, canonical === 1, fixed);
  const hat = new Float64Array(d);
  const coefficients = numbers(2 * phi * psi);
  const reduction = reduced ? numbers(phi * nv) : undefined;
  const puppet = hasPuppet ? readPuppet() : undefined;
  if (at !== bytes.length - 8) fail(`${bytes.length} bytes where its counts need ${at + 8}`);
  /** The puppet's section (Rust's layout): parts, joints, each part, each joint. */
  function readPuppet() {
    const need = (count: number) => {
      if (at + count > bytes.length - 8) fail("the puppet's section ends before its counts say");
    };
    const u32s = (count: number) => {
      need(4 * count);
      const out = new Uint32Array(count);
      for (let k = 0; k < count; k++, at += 4) out[k] = u32(at);
      return out;
    };
    const [partCount, jointCount] = u32s(2) as unknown as [number, number];
    if (partCount < 1 || partCount > 256 || jointCount > nv) fail("the puppet's counts are beyond the limits");
    const parts = [];
    for (let p = 0; p < partCount; p++) {
      const [depth, count, length] = u32s(3) as unknown as [number, number, number];
      if (length > 1024) fail("a part's name is longer than 1024 bytes");
      need(length);
      const name = new TextDecoder("utf-8", { fatal: true }).decode(bytes.subarray(at, at + length));
      at += length;
      const triangles = u32s(count);
      if (triangles.some((t) => t >= nt)) fail("a part names a triangle the mesh does not have");
      parts.push({ name, triangles, depth: depth | 0 });
    }
    need(24 * jointCount);
    const joints = [];
    for (let j = 0; j < jointCount; j++) {
      const [x, y] = f64s(2) as unknown as [number, number];
      const [front, back] = u32s(2) as unknown as [number, number];
      if (front >= partCount || back >= partCount || front === back) fail("a joint names parts it cannot join");
      joints.push({ point: [x, y] as [number, number], parts: [front, back] as [number, number] });
    }
    return { parts, joints };
  }
  const psiValues = new Float64Array(psi);
  const nodal = new Float64Array(2 * phi);
  const inv = 1 / scale;

  return {
    positions,
    triangles,
    vertexCount: nv,
    handleCount: n,
    rest,
    canonical: canonical === 1,
    fixed,
    ...(puppet ?? {}),
    ...(known
      ? {
          training: {
            energy: energy!,
            basis: (["linear", "quadratic", "cubic", "tps"] as const)[kind]!,
            spatial: reduced ? phi : 0,
            samples,
            sampling: sampling!,
            radius,
            seed,
            canonical: canonical === 1,
            fixed: fixed.slice(),
          },
        }
      : {}),
    precision: single ? "single" : "double",
    evaluateInto(targets: ArrayLike<number>, out: Float64Array): void {
      if (targets.length !== d) throw new Error(`targets has ${targets.length} numbers; ${n} handles need ${d}`);
      if (out.length !== 2 * nv) throw new Error(`out has ${out.length} numbers; ${nv} vertices need ${2 * nv}`);
      const motion = canonical ? coordinates.canonicalise(targets, hat) : undefined;
      // Ψ: 1, u = Bᵀ(Q̂ − P) / r_s, then the monomials or the thin-plate functions, in the Rust order.
      psiValues[0] = 1;
      coordinates.project(motion ? hat : targets, inv, psiValues, 1);
      let next = k + 1;
      if (kind === 1 || kind === 2) {
        for (let a = 0; a < k; a++)
          for (let b = a; b < k; b++) psiValues[next++] = psiValues[1 + a]! * psiValues[1 + b]!;
        if (kind === 2) {
          for (let a = 0; a < k; a++)
            for (let b = a; b < k; b++) {
              const ab = psiValues[1 + a]! * psiValues[1 + b]!;
              for (let c = b; c < k; c++) psiValues[next++] = ab * psiValues[1 + c]!;
            }
        }
      } else if (kind === 3) {
        for (let j = 0; j < m; j++) {
          let s = 0;
          for (let a = 0; a < k; a++) {
            const e = psiValues[1 + a]! - centres[j * k + a]!;
            s += e * e;
          }
          psiValues[next++] = s > 0 ? 0.5 * s * Math.log(s) : 0;
        }
      }
      // Each spatial function: its rows of X^x and X^y dotted with Ψ.
      const target = reduction ? nodal : out;
      for (let i = 0; i < phi; i++) {
        let [x, y] = [0, 0];
        const row = 2 * i * psi;
        for (let j = 0; j < psi; j++) {
          x += coefficients[row + j]! * psiValues[j]!;
          y += coefficients[row + psi + j]! * psiValues[j]!;
        }
        if (reduction) [nodal[i], nodal[phi + i]] = [x, y];
        else [target[2 * i], target[2 * i + 1]] = [x, y];
      }
      if (reduction) {
        for (let v = 0; v < nv; v++) {
          let [x, y] = [0, 0];
          for (let i = 0; i < phi; i++) {
            const w = reduction[v * phi + i]!;
            x += nodal[i]! * w;
            y += nodal[phi + i]! * w;
          }
          out[2 * v] = x;
          out[2 * v + 1] = y;
        }
      }
      if (motion) {
        // Back from the canonical pose: R(x − c_P) + c_Q.
        const [cos, sin, tx, ty] = motion;
        const [cx, cy] = coordinates.centroid;
        for (let v = 0; v < nv; v++) {
          const [dx, dy] = [out[2 * v]! - cx, out[2 * v + 1]! - cy];
          out[2 * v] = cos * dx - sin * dy + tx;
          out[2 * v + 1] = sin * dx + cos * dy + ty;
        }
      }
    },
  };
}
