/**
 * The WebGL2 renderer: the mesh as textured triangles (the texture warps with the mesh)
 * and an optional wireframe. Positions are uploaded each frame (converted to float32);
 * texture coordinates, triangles and edges only when the mesh changes.
 *
 * A trained rig on the GPU (`Deformer.setRigOnGpu`) is drawn without positions: its basis
 * texture (RGBA32F, once per rig) and each frame's short vector (the rig's frame, a small
 * RGBA32F texture) go to the vertex shader, which forms each vertex's position as the
 * layout of `RigGpuLayout` says (`x = Σ_t B[v stride + t] · F[head + t]`, likewise y, then
 * the frame's rigid motion), vertex `gl_VertexID`. Flipped triangles are then tinted by the
 * fragment shader (they face backwards), as the overlay tints them otherwise.
 * {@link GlRenderer.shaderPositions} reads the shader's positions back (transform
 * feedback): what the GPU draws, for tests.
 */
import type { RigGpuLayout } from "../../core.js";
import type { View } from "./projection.js";

/** What a frame looks like. Colours are CSS colours (the 2D fallback) or parsed here. */
export interface RenderOptions {
  wireframe: boolean;
  pixelRatio: number;
  background: string;
  /** Flat fill where there is no texture (the 2D fallback). */
  fill: string;
  wire: string;
  /** Tint flipped triangles (the WebGL2 renderer, drawing a rig's frame). */
  flipped?: boolean;
}

/** The part of a renderer the widget uses. */
export interface MeshRenderer {
  readonly kind: "webgl2" | "2d";
  /** Triangles (3 indices each), every edge once (2 each), texture coordinates (2 per vertex). */
  setMesh(triangles: Uint32Array, edges: Uint32Array, uvs: Float32Array): void;
  /** The same triangles in another drawing order (back to front: depth order). */
  setTriangles(triangles: Uint32Array): void;
  setTexture(image: TexImageSource): void;
  /**
   * A rig's basis texture, to draw its frames on the GPU: returns whether this renderer
   * takes it (WebGL2, and a texture within its size limits).
   */
  setRig(layout: RigGpuLayout, texture: Float32Array): boolean;
  /** No rig on the GPU any more. */
  clearRig(): void;
  /**
   * Draws the mesh at `positions` (2 per vertex), or, given `rigFrame`, at the rig's pose
   * the shader forms from that frame (`positions` are then not read).
   */
  draw(positions: ArrayLike<number>, view: View, options: RenderOptions, rigFrame?: Float32Array): void;
  destroy(): void;
}

const VERTEX_SHADER = `#version 300 es
precision highp float;
precision highp int;
in vec2 a_position;
in vec2 a_uv;
uniform vec4 u_transform; // clip = position * xy + zw
uniform bool u_rig; // the position is the rig's, from the basis and the frame
uniform highp sampler2D u_basis;
uniform highp sampler2D u_frame;
uniform ivec4 u_layout; // terms, stride, basisY, frameY (texels)
uniform ivec3 u_widths; // the basis's and the frame's texture widths, the frame's head
out vec2 v_uv;
out vec2 v_shape; // the position in shape units (read back by transform feedback)

vec4 texel(highp sampler2D s, int i, int width) {
  return texelFetch(s, ivec2(i % width, i / width), 0);
}

vec2 rigPosition() {
  int base = gl_VertexID * u_layout.y;
  int head = u_widths.z;
  vec2 p = vec2(0.0);
  for (int t = 0; t < u_layout.x; t++) {
    p.x += dot(texel(u_basis, base + t, u_widths.x), texel(u_frame, head + t, u_widths.y));
    p.y += dot(texel(u_basis, base + u_layout.z + t, u_widths.x), texel(u_frame, head + u_layout.w + t, u_widths.y));
  }
  vec4 rotation = texel(u_frame, 0, u_widths.y); // cos, sin, from
  vec4 to = texel(u_frame, 1, u_widths.y);
  vec2 d = p - rotation.zw;
  return vec2(rotation.x * d.x - rotation.y * d.y, rotation.y * d.x + rotation.x * d.y) + to.xy;
}

void main() {
  v_uv = a_uv;
  vec2 p = u_rig ? rigPosition() : a_position;
  v_shape = p;
  gl_Position = vec4(p * u_transform.xy + u_transform.zw, 0.0, 1.0);
}`;

const FRAGMENT_SHADER = `#version 300 es
precision mediump float;
in vec2 v_uv;
uniform sampler2D u_texture;
uniform vec4 u_color;
uniform bool u_textured;
uniform bool u_flipped;
out vec4 color;
void main() {
  color = u_textured ? texture(u_texture, v_uv) : u_color;
  // A flipped triangle faces backwards (the view keeps counter-clockwise counter-clockwise):
  // the overlay's red at 0.75 over it, premultiplied.
  if (u_flipped && !gl_FrontFacing) color = vec4(0.75 * vec3(0.863, 0.078, 0.235), 0.75) + 0.25 * color;
}`;

/** The rig's texture units: the art is on unit 0. */
const BASIS_UNIT = 1;
const FRAME_UNIT = 2;

/** A rig's textures on the GPU. */
interface GpuRig {
  layout: RigGpuLayout;
  basis: WebGLTexture;
  frame: WebGLTexture;
  basisWidth: number;
  frameWidth: number;
  frameHeight: number;
  /** The frame padded to whole rows, when it needs padding. */
  padded: Float32Array | undefined;
}

export class GlRenderer implements MeshRenderer {
  readonly kind = "webgl2";
  readonly #gl: WebGL2RenderingContext;
  readonly #program: WebGLProgram;
  readonly #vao: WebGLVertexArrayObject;
  readonly #positionBuffer: WebGLBuffer;
  readonly #uvBuffer: WebGLBuffer;
  readonly #triangleBuffer: WebGLBuffer;
  readonly #edgeBuffer: WebGLBuffer;
  readonly #texture: WebGLTexture;
  readonly #uniforms: Uniforms;
  #positions = new Float32Array(0);
  #vertexCount = 0;
  #rig: GpuRig | undefined;
  #triangleCount = 0;
  #edgeCount = 0;

  /** Throws when the browser has no WebGL2 (the caller then falls back to 2D). */
  constructor(canvas: HTMLCanvasElement) {
    const gl = canvas.getContext("webgl2", { antialias: true, preserveDrawingBuffer: true, premultipliedAlpha: true });
    if (!gl) throw new Error("WebGL2 is not available");
    this.#gl = gl;
    this.#program = link(gl, VERTEX_SHADER, FRAGMENT_SHADER, ["v_shape"]);
    const uniform = (name: string): WebGLUniformLocation => {
      const location = gl.getUniformLocation(this.#program, `u_${name}`);
      if (!location) throw new Error(`the shader has no uniform u_${name}`);
      return location;
    };
    this.#uniforms = Object.fromEntries(UNIFORMS.map((name) => [name, uniform(name)])) as Uniforms;
    gl.useProgram(this.#program);
    gl.uniform1i(this.#uniforms.basis, BASIS_UNIT);
    gl.uniform1i(this.#uniforms.frame, FRAME_UNIT);
    gl.useProgram(null);
    this.#vao = gl.createVertexArray();
    this.#positionBuffer = gl.createBuffer();
    this.#uvBuffer = gl.createBuffer();
    this.#triangleBuffer = gl.createBuffer();
    this.#edgeBuffer = gl.createBuffer();
    gl.bindVertexArray(this.#vao);
    for (const [name, buffer] of [
      ["a_position", this.#positionBuffer],
      ["a_uv", this.#uvBuffer],
    ] as const) {
      const location = gl.getAttribLocation(this.#program, name);
      gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
      gl.enableVertexAttribArray(location);
      gl.vertexAttribPointer(location, 2, gl.FLOAT, false, 0, 0);
    }
    gl.bindVertexArray(null);
    this.#texture = gl.createTexture();
    // A 1x1 placeholder until a texture is set.
    gl.bindTexture(gl.TEXTURE_2D, this.#texture);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, 1, 1, 0, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array([200, 119, 58, 255]));
  }

  setMesh(triangles: Uint32Array, edges: Uint32Array, uvs: Float32Array): void {
    const gl = this.#gl;
    this.#positions = new Float32Array(uvs.length);
    gl.bindVertexArray(this.#vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.#positionBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, this.#positions.byteLength, gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.#uvBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, uvs, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.#triangleBuffer);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, triangles, gl.STATIC_DRAW);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.#edgeBuffer);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, edges, gl.STATIC_DRAW);
    this.#triangleCount = triangles.length;
    this.#edgeCount = edges.length;
    this.#vertexCount = uvs.length / 2;
  }

  setTriangles(triangles: Uint32Array): void {
    const gl = this.#gl;
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.#triangleBuffer);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, triangles, gl.STATIC_DRAW);
    this.#triangleCount = triangles.length;
  }

  setTexture(image: TexImageSource): void {
    const gl = this.#gl;
    gl.bindTexture(gl.TEXTURE_2D, this.#texture);
    // Texture coordinates have v up, images have rows top down. The blending takes
    // premultiplied colours, so translucent texels (vector art's fill-opacity) are
    // premultiplied on upload.
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, true);
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, true);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, gl.RGBA, gl.UNSIGNED_BYTE, image);
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    gl.generateMipmap(gl.TEXTURE_2D);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  }

  setRig(layout: RigGpuLayout, texture: Float32Array): boolean {
    const gl = this.#gl;
    this.clearRig();
    const most = gl.getParameter(gl.MAX_TEXTURE_SIZE) as number;
    const texels = layout.vertexCount * layout.stride;
    if (layout.vertexCount !== this.#vertexCount || texture.length !== 4 * texels) return false;
    const basisWidth = Math.min(most, 4096);
    const basisHeight = Math.max(1, Math.ceil(texels / basisWidth));
    const frameWidth = Math.min(most, layout.frameTexels);
    const frameHeight = Math.ceil(layout.frameTexels / frameWidth);
    if (basisHeight > most || frameHeight > most) return false;
    const padded = (data: Float32Array, rows: number, width: number): Float32Array => {
      if (data.length === 4 * width * rows) return data;
      const out = new Float32Array(4 * width * rows);
      out.set(data);
      return out;
    };
    const upload = (unit: number, width: number, height: number, data: Float32Array | null): WebGLTexture => {
      const made = gl.createTexture();
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, made);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, width, height, 0, gl.RGBA, gl.FLOAT, data);
      // Read by texelFetch only: no filtering (float textures cannot be filtered anyway).
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      gl.activeTexture(gl.TEXTURE0);
      return made;
    };
    const basis = upload(BASIS_UNIT, basisWidth, basisHeight, padded(texture, basisHeight, basisWidth));
    const frame = upload(FRAME_UNIT, frameWidth, frameHeight, null);
    const needsPadding = frameWidth * frameHeight !== layout.frameTexels;
    const framePadding = needsPadding ? new Float32Array(4 * frameWidth * frameHeight) : undefined;
    this.#rig = { layout, basis, frame, basisWidth, frameWidth, frameHeight, padded: framePadding };
    return true;
  }

  clearRig(): void {
    if (!this.#rig) return;
    this.#gl.deleteTexture(this.#rig.basis);
    this.#gl.deleteTexture(this.#rig.frame);
    this.#rig = undefined;
  }

  /**
   * The shader's uniforms and textures for a frame: from `positions` (uploaded), or from the
   * rig's frame (uploaded to its texture).
   */
  #prepare(positions: ArrayLike<number>, rigFrame: Float32Array | undefined): void {
    const gl = this.#gl;
    gl.useProgram(this.#program);
    gl.bindVertexArray(this.#vao);
    const rig = rigFrame && this.#rig;
    gl.uniform1i(this.#uniforms.rig, rig ? 1 : 0);
    if (rig) {
      const { layout } = rig;
      let data = rigFrame;
      if (rig.padded) {
        rig.padded.set(rigFrame);
        data = rig.padded;
      }
      gl.activeTexture(gl.TEXTURE0 + FRAME_UNIT);
      gl.bindTexture(gl.TEXTURE_2D, rig.frame);
      gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, rig.frameWidth, rig.frameHeight, gl.RGBA, gl.FLOAT, data);
      gl.activeTexture(gl.TEXTURE0 + BASIS_UNIT);
      gl.bindTexture(gl.TEXTURE_2D, rig.basis);
      gl.activeTexture(gl.TEXTURE0);
      gl.uniform4i(this.#uniforms.layout, layout.terms, layout.stride, layout.basisY, layout.frameY);
      gl.uniform3i(this.#uniforms.widths, rig.basisWidth, rig.frameWidth, layout.rigidTexels);
      return;
    }
    const scratch = this.#positions;
    for (let i = 0; i < scratch.length; i++) scratch[i] = positions[i]!;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.#positionBuffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, scratch);
  }

  draw(positions: ArrayLike<number>, view: View, options: RenderOptions, rigFrame?: Float32Array): void {
    const gl = this.#gl;
    const { width, height } = gl.canvas;
    gl.viewport(0, 0, width, height);
    const [r, g, b, a] = parseColor(options.background);
    gl.clearColor(r, g, b, a);
    gl.clear(gl.COLOR_BUFFER_BIT);
    if (this.#triangleCount === 0) return;

    this.#prepare(positions, rigFrame);
    gl.uniform1i(this.#uniforms.flipped, rigFrame && this.#rig && options.flipped ? 1 : 0);
    // Shape units to clip space through the view (pixels, y down).
    gl.uniform4f(
      this.#uniforms.transform,
      (2 * view.scale) / width,
      (2 * view.scale) / height,
      (2 * view.offsetX) / width - 1,
      1 - (2 * view.offsetY) / height,
    );
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.ONE, gl.ONE_MINUS_SRC_ALPHA);

    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, this.#texture);
    gl.uniform1i(this.#uniforms.textured, 1);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.#triangleBuffer);
    gl.drawElements(gl.TRIANGLES, this.#triangleCount, gl.UNSIGNED_INT, 0);

    if (options.wireframe && this.#edgeCount > 0) {
      gl.uniform1i(this.#uniforms.textured, 0);
      gl.uniform1i(this.#uniforms.flipped, 0);
      const [wr, wg, wb, wa] = parseColor(options.wire);
      gl.uniform4f(this.#uniforms.color, wr * wa, wg * wa, wb * wa, wa);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.#edgeBuffer);
      gl.drawElements(gl.LINES, this.#edgeCount, gl.UNSIGNED_INT, 0);
    }
    gl.bindVertexArray(null);
  }

  /**
   * The positions the vertex shader forms (2 per vertex, single precision), read back by
   * transform feedback: from `positions` or, given `rigFrame`, from the rig's frame, as
   * {@link draw} would draw them. For tests and diagnostics (it waits for the GPU).
   */
  shaderPositions(positions: ArrayLike<number>, rigFrame?: Float32Array): Float32Array {
    const gl = this.#gl;
    const out = new Float32Array(2 * this.#vertexCount);
    if (this.#vertexCount === 0) return out;
    this.#prepare(positions, rigFrame);
    const buffer = gl.createBuffer();
    const feedback = gl.createTransformFeedback();
    gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, buffer);
    gl.bufferData(gl.TRANSFORM_FEEDBACK_BUFFER, out.byteLength, gl.STREAM_READ);
    gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, feedback);
    gl.bindBufferBase(gl.TRANSFORM_FEEDBACK_BUFFER, 0, buffer);
    gl.enable(gl.RASTERIZER_DISCARD);
    gl.beginTransformFeedback(gl.POINTS);
    gl.drawArrays(gl.POINTS, 0, this.#vertexCount);
    gl.endTransformFeedback();
    gl.disable(gl.RASTERIZER_DISCARD);
    gl.bindBufferBase(gl.TRANSFORM_FEEDBACK_BUFFER, 0, null);
    gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, null);
    gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, buffer);
    gl.getBufferSubData(gl.TRANSFORM_FEEDBACK_BUFFER, 0, out);
    gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, null);
    gl.deleteBuffer(buffer);
    gl.deleteTransformFeedback(feedback);
    gl.bindVertexArray(null);
    return out;
  }

  destroy(): void {
    const gl = this.#gl;
    this.clearRig();
    for (const buffer of [this.#positionBuffer, this.#uvBuffer, this.#triangleBuffer, this.#edgeBuffer]) {
      gl.deleteBuffer(buffer);
    }
    gl.deleteTexture(this.#texture);
    gl.deleteVertexArray(this.#vao);
    gl.deleteProgram(this.#program);
  }
}

/** The shaders' uniforms, without their `u_` prefix. */
const UNIFORMS = ["transform", "color", "textured", "flipped", "rig", "basis", "frame", "layout", "widths"] as const;
type Uniforms = Record<(typeof UNIFORMS)[number], WebGLUniformLocation>;

/** The program of two shaders; `varyings` are captured by transform feedback. */
function link(gl: WebGL2RenderingContext, vertex: string, fragment: string, varyings: string[]): WebGLProgram {
  const program = gl.createProgram();
  for (const [type, source] of [
    [gl.VERTEX_SHADER, vertex],
    [gl.FRAGMENT_SHADER, fragment],
  ] as const) {
    const shader = gl.createShader(type);
    if (!shader) throw new Error("WebGL2 could not create a shader");
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
      throw new Error(`a shader did not compile: ${gl.getShaderInfoLog(shader) ?? "no log"}`);
    }
    gl.attachShader(program, shader);
    gl.deleteShader(shader);
  }
  gl.transformFeedbackVaryings(program, varyings, gl.SEPARATE_ATTRIBS);
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
    throw new Error(`the shaders did not link: ${gl.getProgramInfoLog(program) ?? "no log"}`);
  }
  return program;
}

/** `#rrggbb` or `rgba(r, g, b, a)` to components in [0, 1]. */
export function parseColor(css: string): [number, number, number, number] {
  const hex = /^#([0-9a-f]{2})([0-9a-f]{2})([0-9a-f]{2})$/i.exec(css);
  if (hex) return [parseInt(hex[1]!, 16) / 255, parseInt(hex[2]!, 16) / 255, parseInt(hex[3]!, 16) / 255, 1];
  const rgba = /^rgba?\(\s*([\d.]+)\s*,\s*([\d.]+)\s*,\s*([\d.]+)\s*(?:,\s*([\d.]+)\s*)?\)$/i.exec(css);
  if (rgba) {
    return [
      Number(rgba[1]) / 255,
      Number(rgba[2]) / 255,
      Number(rgba[3]) / 255,
      rgba[4] === undefined ? 1 : Number(rgba[4]),
    ];
  }
  throw new Error(`cannot read the colour ${css}`);
}
