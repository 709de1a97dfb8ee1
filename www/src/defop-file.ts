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
  /** Writes the vertex positions (2 per vertex) for handle targets (2 per handle) to `out`. */
  evaluateInto(targets: ArrayLike<number>, out: Float64Array): void;
}

const MAGIC = "AKAPDEFO";
const HEADER = 48;

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

/** Reads and checks an operator file; throws an `Error` saying what is wrong. */
export function readOperatorFile(bytes: Uint8Array): OperatorFile {
  const fail = (why: string): never => {
    throw new Error(`not a usable operator file: ${why}`);
  };
  if (bytes.length < HEADER + 8 || String.fromCharCode(...bytes.subarray(0, 8)) !== MAGIC) fail("no AKAPDEFO header");
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const u32 = (at: number) => view.getUint32(at, true);
  if (u32(8) !== 1) fail(`version ${u32(8)} (only 1 is read)`);
  const [nv, nt, n, m, phi] = [12, 16, 20, 24, 28].map(u32) as [number, number, number, number, number];
  const [kind, reduced] = [bytes[32]!, bytes[33]!];
  if (kind > 3 || reduced > 1 || n === 0 || nv < 3) fail("a field holds a value no writer writes");
  const d = 2 * n;
  const psi = [d + 1, 1 + d + (d * (d + 1)) / 2, 1 + d + (d * (d + 1)) / 2 + (d * (d + 1) * (d + 2)) / 6, d + 1 + m][
    kind
  ]!;
  const expected = HEADER + 16 * nv + 12 * nt + 48 * n + 16 * n * m + 16 * phi * psi + (reduced ? 8 * phi * nv : 0) + 8;
  if (bytes.length !== expected) fail(`${bytes.length} bytes where its counts need ${expected}`);
  const [hi, lo] = fnv1a(bytes.subarray(0, bytes.length - 8));
  if (u32(bytes.length - 8) !== lo || u32(bytes.length - 4) !== hi) fail("the checksum does not match");

  let at = HEADER;
  const f64s = (count: number) => {
    const out = new Float64Array(count);
    for (let k = 0; k < count; k++, at += 8) out[k] = view.getFloat64(at, true);
    return out;
  };
  const scale = view.getFloat64(40, true);
  const positions = f64s(2 * nv);
  const triangles = new Uint32Array(3 * nt);
  for (let k = 0; k < 3 * nt; k++, at += 4) triangles[k] = u32(at);
  at += 32 * n; // the handles' places on the mesh: not needed to evaluate
  const rest = f64s(d);
  const centres = f64s(d * m);
  const coefficients = f64s(2 * phi * psi);
  const reduction = reduced ? f64s(phi * nv) : undefined;
  const psiValues = new Float64Array(psi);
  const nodal = new Float64Array(2 * phi);
  const inv = 1 / scale;

  return {
    positions,
    triangles,
    vertexCount: nv,
    handleCount: n,
    rest,
    evaluateInto(targets: ArrayLike<number>, out: Float64Array): void {
      if (targets.length !== d) throw new Error(`targets has ${targets.length} numbers; ${n} handles need ${d}`);
      if (out.length !== 2 * nv) throw new Error(`out has ${out.length} numbers; ${nv} vertices need ${2 * nv}`);
      // Ψ: 1, u, then the monomials or the thin-plate functions, in the Rust order.
      psiValues[0] = 1;
      for (let a = 0; a < d; a++) psiValues[1 + a] = (targets[a]! - rest[a]!) * inv;
      let k = d + 1;
      if (kind === 1 || kind === 2) {
        for (let a = 0; a < d; a++) for (let b = a; b < d; b++) psiValues[k++] = psiValues[1 + a]! * psiValues[1 + b]!;
        if (kind === 2) {
          for (let a = 0; a < d; a++)
            for (let b = a; b < d; b++) {
              const ab = psiValues[1 + a]! * psiValues[1 + b]!;
              for (let c = b; c < d; c++) psiValues[k++] = ab * psiValues[1 + c]!;
            }
        }
      } else if (kind === 3) {
        for (let j = 0; j < m; j++) {
          let s = 0;
          for (let a = 0; a < d; a++) {
            const e = psiValues[1 + a]! - centres[j * d + a]!;
            s += e * e;
          }
          psiValues[k++] = s > 0 ? 0.5 * s * Math.log(s) : 0;
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
    },
  };
}
