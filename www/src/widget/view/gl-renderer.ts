/**
 * The WebGL2 renderer: the mesh as textured triangles (the texture warps with the mesh)
 * and an optional wireframe. Positions are uploaded each frame (converted to float32);
 * texture coordinates, triangles and edges only when the mesh changes.
 */
import type { View } from "./projection.js";

/** What a frame looks like. Colours are CSS colours (the 2D fallback) or parsed here. */
export interface RenderOptions {
  wireframe: boolean;
  pixelRatio: number;
  background: string;
  /** Flat fill where there is no texture (the 2D fallback). */
  fill: string;
  wire: string;
}

/** The part of a renderer the widget uses. */
export interface MeshRenderer {
  readonly kind: "webgl2" | "2d";
  /** Triangles (3 indices each), every edge once (2 each), texture coordinates (2 per vertex). */
  setMesh(triangles: Uint32Array, edges: Uint32Array, uvs: Float32Array): void;
  /** The same triangles in another drawing order (back to front: depth order). */
  setTriangles(triangles: Uint32Array): void;
  setTexture(image: TexImageSource): void;
  draw(positions: ArrayLike<number>, view: View, options: RenderOptions): void;
  destroy(): void;
}

const VERTEX_SHADER = `#version 300 es
in vec2 a_position;
in vec2 a_uv;
uniform vec4 u_transform; // clip = position * xy + zw
out vec2 v_uv;
void main() {
  v_uv = a_uv;
  gl_Position = vec4(a_position * u_transform.xy + u_transform.zw, 0.0, 1.0);
}`;

const FRAGMENT_SHADER = `#version 300 es
precision mediump float;
in vec2 v_uv;
uniform sampler2D u_texture;
uniform vec4 u_color;
uniform bool u_textured;
out vec4 color;
void main() {
  color = u_textured ? texture(u_texture, v_uv) : u_color;
}`;

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
  readonly #uniforms: { transform: WebGLUniformLocation; color: WebGLUniformLocation; textured: WebGLUniformLocation };
  #positions = new Float32Array(0);
  #triangleCount = 0;
  #edgeCount = 0;

  /** Throws when the browser has no WebGL2 (the caller then falls back to 2D). */
  constructor(canvas: HTMLCanvasElement) {
    const gl = canvas.getContext("webgl2", { antialias: true, preserveDrawingBuffer: true, premultipliedAlpha: true });
    if (!gl) throw new Error("WebGL2 is not available");
    this.#gl = gl;
    this.#program = link(gl, VERTEX_SHADER, FRAGMENT_SHADER);
    const uniform = (name: string): WebGLUniformLocation => {
      const location = gl.getUniformLocation(this.#program, name);
      if (!location) throw new Error(`the shader has no uniform ${name}`);
      return location;
    };
    this.#uniforms = { transform: uniform("u_transform"), color: uniform("u_color"), textured: uniform("u_textured") };
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

  draw(positions: ArrayLike<number>, view: View, options: RenderOptions): void {
    const gl = this.#gl;
    const { width, height } = gl.canvas;
    gl.viewport(0, 0, width, height);
    const [r, g, b, a] = parseColor(options.background);
    gl.clearColor(r, g, b, a);
    gl.clear(gl.COLOR_BUFFER_BIT);
    if (this.#triangleCount === 0) return;

    const scratch = this.#positions;
    // A typed array converts natively (a JavaScript loop over 100,000 numbers costs about
    // a millisecond at 50,000 vertices).
    if (positions instanceof Float64Array && positions.length === scratch.length) scratch.set(positions);
    else for (let i = 0; i < scratch.length; i++) scratch[i] = positions[i]!;
    gl.useProgram(this.#program);
    gl.bindVertexArray(this.#vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.#positionBuffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, scratch);
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
      const [wr, wg, wb, wa] = parseColor(options.wire);
      gl.uniform4f(this.#uniforms.color, wr * wa, wg * wa, wb * wa, wa);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.#edgeBuffer);
      gl.drawElements(gl.LINES, this.#edgeCount, gl.UNSIGNED_INT, 0);
    }
    gl.bindVertexArray(null);
  }

  destroy(): void {
    const gl = this.#gl;
    for (const buffer of [this.#positionBuffer, this.#uvBuffer, this.#triangleBuffer, this.#edgeBuffer]) {
      gl.deleteBuffer(buffer);
    }
    gl.deleteTexture(this.#texture);
    gl.deleteVertexArray(this.#vao);
    gl.deleteProgram(this.#program);
  }
}

function link(gl: WebGL2RenderingContext, vertex: string, fragment: string): WebGLProgram {
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
